// Browser test of the replay viewer (/replay) against the real server: it opens the log `serve --replay` serves,
// says that every recorded hash matches this browser, and scrubbing to a tick (forward, then back past a jump)
// shows exactly the state Node computed for that tick; a log with one doctored hash is opened from the file picker
// and the viewer names that tick as where the recorded hashes stop matching; without WebGPU it still checks a log.
import { mkdtemp, rm, writeFile } from 'node:fs/promises';
import { tmpdir } from 'node:os';
import { join } from 'node:path';
import type { Page } from 'playwright-core';
import { afterAll, beforeAll, expect, it } from 'vitest';
import '../../server/physics-node.ts';
import { getScenario } from '../../scenarios/index.ts';
import { LogEncoder } from '../../server/log/log-encoder.ts';
import { silentLogger } from '../../server/logger.ts';
import { createMetrics } from '../../server/metrics.ts';
import { startServer, type RunningServer } from '../../server/start-server.ts';
import { buildClient } from '../../scripts/build-client.ts';
import { BotScript } from '../../shared/sim/bots.ts';
import { Simulation } from '../../shared/sim/simulation.ts';
import { canvasPixels, describeBrowser, dominantColor, fractionUnlike, launchBrowser, type BrowserSession } from '../helpers/browser.ts';

const SCENARIO = 'character-course';
const SEED = 77;
const TICKS = 300;
const HASH_EVERY_TICKS = 10;
/** The doctored log's wrong hash is at this tick counter. */
const DOCTORED_TICK = 120;

/** What Node computed at one tick: the state hash and every moving body's position. */
interface NodeTick {
  hash: string;
  positions: Map<number, [number, number, number]>;
}

interface Recording {
  bytes: Uint8Array;
  doctored: Uint8Array;
  ticks: NodeTick[];
  hashesRecorded: number;
}

/** Bots play the scenario in Node; the log records a hash every HASH_EVERY_TICKS ticks (one doctored in the copy). */
async function record(): Promise<Recording> {
  const sim = await Simulation.create({ scenario: getScenario(SCENARIO), seed: SEED });
  const header = { joltVersion: '1.1.0', scenario: SCENARIO, params: {}, seed: SEED, tickRateHz: 60, hashEveryTicks: HASH_EVERY_TICKS, checkpointEveryTicks: 0, createdBy: 'tests' };
  const good = new LogEncoder(header);
  const bad = new LogEncoder(header);
  const parts: Uint8Array[] = [good.start()];
  const doctored: Uint8Array[] = [bad.start()];
  const ticks: NodeTick[] = [];
  let hashesRecorded = 0;
  const note = (): void => {
    const read = sim.readBodyStates();
    const positions = new Map<number, [number, number, number]>();
    for (let i = 0; i < read.count; i++) if ((read.flags[i] & 1) === 0) positions.set(read.ids[i], [read.states[i * 13], read.states[i * 13 + 1], read.states[i * 13 + 2]]);
    ticks.push({ hash: sim.stateHash(), positions });
  };
  try {
    const script = new BotScript({ seed: SEED, bots: 3, joinTicks: [0, 40, 150], leaveTicks: [-1, 220, -1] });
    note();
    for (let t = 0; t < TICKS; t++) {
      const rec = script.next();
      sim.step(rec);
      parts.push(good.tick(rec));
      doctored.push(bad.tick(rec));
      note();
      if (sim.tick % HASH_EVERY_TICKS === 0) {
        const hash = sim.stateHash();
        parts.push(good.hash(sim.tick, hash));
        doctored.push(bad.hash(sim.tick, sim.tick === DOCTORED_TICK ? `${hash.slice(0, 15)}${hash[15] === '0' ? '1' : '0'}` : hash));
        hashesRecorded++;
      }
    }
    parts.push(good.end(sim.tick, sim.stateHash()));
    doctored.push(bad.end(sim.tick, sim.stateHash()));
    hashesRecorded++;
  } finally {
    sim.destroy();
  }
  return { bytes: Buffer.concat(parts), doctored: Buffer.concat(doctored), ticks, hashesRecorded };
}

type ReplayHook = {
  phase: string;
  error: string | null;
  tick: number;
  lastTick: number;
  renderedTick: number;
  stateHash: string | null;
  verification: { hashesChecked: number; firstMismatchTick: number | null } | null;
  drawn: Array<{ id: number; pose: number[] | null }>;
  follow: number | null;
};

async function hook(page: Page): Promise<ReplayHook> {
  return page.evaluate(() => JSON.parse(JSON.stringify((globalThis as { __taosReplay?: unknown }).__taosReplay ?? null)) as never);
}

async function waitForReplay(page: Page, predicate: string, timeoutMs = 60_000): Promise<void> {
  await page.waitForFunction(`(() => { const t = globalThis.__taosReplay; return !!t && (${predicate}); })()`, null, { timeout: timeoutMs, polling: 100 });
}

/** Scrubs to `tick` with the slider and checks the drawn frame is Node's state of that tick. */
async function scrubAndCheck(page: Page, rec: Recording, tick: number): Promise<void> {
  await page.locator('#scrub').fill(String(tick));
  await waitForReplay(page, `t.tick === ${tick} && t.renderedTick === ${tick}`);
  // One more frame, so the poses read back are the ones drawn for this tick.
  await page.evaluate(() => new Promise<void>((resolve) => requestAnimationFrame(() => requestAnimationFrame(() => resolve()))));
  const h = await hook(page);
  expect(h.tick).toBe(tick);
  expect(h.stateHash, `the state shown at tick ${tick}`).toBe(rec.ticks[tick].hash);
  const expected = rec.ticks[tick].positions;
  expect(h.drawn.map((d) => d.id).sort((a, b) => a - b)).toEqual([...expected.keys()].sort((a, b) => a - b));
  for (const d of h.drawn) {
    const want = expected.get(d.id)!;
    expect(d.pose, `body ${d.id} is drawn at tick ${tick}`).not.toBeNull();
    for (let k = 0; k < 3; k++) expect(Math.abs(d.pose![k] - want[k]), `body ${d.id} axis ${k} at tick ${tick}`).toBeLessThan(1e-4);
  }
}

describeBrowser('replay viewer', () => {
  let browser: BrowserSession;
  let server: RunningServer;
  let rec: Recording;
  let dir: string;

  beforeAll(async () => {
    rec = await record();
    dir = await mkdtemp(join(tmpdir(), 'taos-replay-'));
    await writeFile(join(dir, 'session.taoslog'), rec.bytes);
    await writeFile(join(dir, 'doctored.taoslog'), rec.doctored);
    const built = await buildClient();
    server = await startServer({ port: 0, host: '127.0.0.1', scenario: 'pendulum-chain', clientDir: built.outDir, replayFile: join(dir, 'session.taoslog'), logger: silentLogger(), metrics: createMetrics({ processMetrics: false }) });
    browser = await launchBrowser();
  }, 120_000);

  afterAll(async () => {
    await browser?.close();
    await server?.close('test over');
    if (dir) await rm(dir, { recursive: true, force: true });
  });

  it('opens the served log, finds every recorded hash matching, and scrubbing to a tick shows that tick', async () => {
    const { page, errors } = await browser.newPage();
    await page.goto(new URL('/replay', server.url).href);
    await waitForReplay(page, "t.phase === 'ready' || t.phase === 'error'");
    const h = await hook(page);
    expect(h.error).toBeNull();
    expect(h.lastTick).toBe(TICKS);
    expect(h.verification).toEqual({ hashesChecked: rec.hashesRecorded, firstMismatchTick: null, expected: null, actual: null, failure: null });
    await expect(page.locator('#verify-status').textContent()).resolves.toBe(`All ${rec.hashesRecorded} recorded hashes match this browser`);
    expect(h.follow).toBe(1);

    await scrubAndCheck(page, rec, 170);
    await scrubAndCheck(page, rec, 171);
    await scrubAndCheck(page, rec, 45);
    await scrubAndCheck(page, rec, TICKS);
    const shot = await canvasPixels(page);
    expect(fractionUnlike(shot, dominantColor(shot))).toBeGreaterThan(0.1);

    await scrubAndCheck(page, rec, 0);
    await page.locator('#speed').selectOption('4');
    await page.locator('#play').click();
    await waitForReplay(page, 't.tick >= 60', 30_000);
    await page.locator('#play').click();
    const paused = (await hook(page)).tick;
    await page.waitForTimeout(300);
    expect((await hook(page)).tick).toBe(paused);
    expect(errors).toEqual([]);
    await page.close();
  });

  it('still checks the served log in a browser without WebGPU, and says that nothing is drawn', async () => {
    const { page, errors } = await browser.newPage();
    await page.addInitScript(() => {
      Object.defineProperty(Navigator.prototype, 'gpu', { get: () => undefined, configurable: true });
    });
    await page.goto(new URL('/replay', server.url).href);
    await waitForReplay(page, "t.phase === 'ready' || t.phase === 'error'");
    const h = await hook(page);
    expect(h.verification?.hashesChecked).toBe(rec.hashesRecorded);
    expect(h.verification?.firstMismatchTick).toBeNull();
    await expect(page.locator('#message h2').textContent()).resolves.toBe('WebGPU is not available');
    await expect(page.locator('#message p').textContent()).resolves.toMatch(/recorded hashes checked; nothing is drawn/);
    await page.locator('#scrub').fill('170');
    await waitForReplay(page, 't.tick === 170');
    expect((await hook(page)).stateHash).toBe(rec.ticks[170].hash);
    expect(errors).toEqual([]);
    await page.close();
  });

  it('names the tick where a log with a doctored hash stops matching this browser, opened from the file picker', async () => {
    const { page, errors } = await browser.newPage();
    await page.goto(new URL('/replay', server.url).href);
    await waitForReplay(page, "t.phase === 'ready'");
    await page.locator('#log-file').setInputFiles(join(dir, 'doctored.taoslog'));
    await waitForReplay(page, "t.phase === 'ready' && t.source === 'doctored.taoslog'");
    const h = await hook(page);
    expect(h.verification?.firstMismatchTick).toBe(DOCTORED_TICK);
    await expect(page.locator('#verify-status').textContent()).resolves.toMatch(new RegExp(`^Recorded hashes stop matching this browser at tick ${DOCTORED_TICK} \\(recorded [0-9a-f]{16}, this browser ${rec.ticks[DOCTORED_TICK].hash}\\)$`));
    expect(errors).toEqual([]);
    await page.close();
  });
});
