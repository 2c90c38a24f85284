// The Simulation as the client build ships it (the physics chunk pages import()) reproduces Node bit for bit, in
// headless Chromium and Firefox ESR: every scenario's golden run ends on its committed hash, and a checkpoint made in Node restores in the browser and
// continues (through a join, a leave and a fast rollback) with the same hash on every tick as in Node.
import { readFileSync } from 'node:fs';
import { fileURLToPath } from 'node:url';
import { afterAll, beforeAll, expect, it } from 'vitest';
import '../../../server/physics-node.ts';
import { listScenarios } from '../../../scenarios/index.ts';
import { BotScript } from '../../../shared/sim/bots.ts';
import { GOLDEN_SEED, parseGoldenFile } from '../../../shared/sim/golden.ts';
import type { ScenarioDefinition } from '../../../shared/sim/scenario.ts';
import { Simulation } from '../../../shared/sim/simulation.ts';
import { describeBrowser, launchBrowser } from '../../helpers/browser.ts';
import { describeFirefox, openInFirefox } from '../../helpers/firefox.ts';
import { startSimCheckHost, type SimCheckHost } from '../../helpers/sim-check/host.ts';
import type { ResumeJob, SimCheckResult } from '../../helpers/sim-check/protocol.ts';

/** Ticks Node runs before saving the checkpoint the browser resumes from. */
const CHECKPOINT_TICK = 90;
/** Ticks the browser plays after restoring. */
const RESUME_TICKS = 90;
/** The browser saves a fast checkpoint this many records in and rolls back to it at the end. */
const FAST_ROLLBACK_AT = 30;
const RESULT_TIMEOUT_MS = 240_000;

interface NodeResume {
  job: ResumeJob;
  hashes: string[];
}

function goldenHash(name: string): string {
  const path = fileURLToPath(new URL(`../../../scenarios/${name}.golden.json`, import.meta.url));
  return parseGoldenFile(JSON.parse(readFileSync(path, 'utf8')), path).hash;
}

/** Node plays a scenario to CHECKPOINT_TICK, saves the checkpoint bytes, then records the next ticks' inputs and hashes. */
async function nodeResume(scenario: ScenarioDefinition): Promise<NodeResume> {
  const sim = await Simulation.create({ scenario, seed: GOLDEN_SEED });
  try {
    // One bot from the start, one who joins after the checkpoint and leaves again before the end.
    const script = new BotScript({ seed: GOLDEN_SEED, bots: 2, joinTicks: [5, CHECKPOINT_TICK + 20], leaveTicks: [-1, CHECKPOINT_TICK + 70] });
    for (let t = 0; t < CHECKPOINT_TICK; t++) sim.step(script.next());
    const checkpoint = sim.saveCheckpointBytes();
    const records = [];
    const hashes: string[] = [];
    for (let t = 0; t < RESUME_TICKS; t++) {
      const record = script.next();
      records.push(record);
      sim.step(record);
      hashes.push(sim.stateHash());
    }
    return { job: { scenario: scenario.name, seed: GOLDEN_SEED, checkpointB64: Buffer.from(checkpoint).toString('base64'), records, fastCheckpointAfter: FAST_ROLLBACK_AT }, hashes };
  } finally {
    sim.destroy();
  }
}

function checkResult(result: SimCheckResult, node: readonly NodeResume[]): void {
  expect(result.error, `the page failed (${result.userAgent})`).toBeNull();
  const scenarios = listScenarios().map((d) => d.name);
  expect(result.goldens.map((g) => g.scenario)).toEqual(scenarios);
  for (const g of result.goldens) {
    expect(g.hash, `${g.scenario}: the golden run in ${result.userAgent} departs from the committed hash (hash every 60 ticks: ${JSON.stringify(g.checkpoints)})`).toBe(goldenHash(g.scenario));
  }
  expect(result.resumes.map((r) => r.scenario)).toEqual(node.map((n) => n.job.scenario));
  for (let i = 0; i < node.length; i++) {
    const mine = result.resumes[i];
    const theirs = node[i];
    expect(mine.restoredTick).toBe(CHECKPOINT_TICK);
    const firstDiff = theirs.hashes.findIndex((h, k) => mine.hashes[k] !== h);
    expect(firstDiff, `${mine.scenario}: the browser leaves Node at tick ${CHECKPOINT_TICK + firstDiff + 1} after restoring Node's checkpoint`).toBe(-1);
    expect(mine.hashes).toHaveLength(RESUME_TICKS);
    expect(mine.rerunFrom).toBe(FAST_ROLLBACK_AT);
    expect(mine.rerunHashes, `${mine.scenario}: replaying after a fast rollback gives other hashes`).toEqual(theirs.hashes.slice(FAST_ROLLBACK_AT));
  }
}

let host: SimCheckHost;
let node: NodeResume[];

beforeAll(async () => {
  node = [];
  for (const def of listScenarios()) node.push(await nodeResume(def));
  host = await startSimCheckHost(node.map((n) => n.job));
}, 180_000);

afterAll(async () => {
  await host?.close();
});

describeBrowser('Simulation in Chromium', () => {
  it('reproduces every golden hash and continues a Node checkpoint with the same hash on every tick', async () => {
    const browser = await launchBrowser();
    try {
      const { page, errors } = await browser.newPage();
      const result = host.nextResult(RESULT_TIMEOUT_MS);
      await page.goto(host.url);
      checkResult(await result, node);
      expect(errors).toEqual([]);
    } finally {
      await browser.close();
    }
  }, RESULT_TIMEOUT_MS + 30_000);
});

describeFirefox('Simulation in Firefox ESR', () => {
  it('reproduces every golden hash and continues a Node checkpoint with the same hash on every tick', async () => {
    const firefox = await openInFirefox(host.url);
    try {
      const result = await Promise.race([
        host.nextResult(RESULT_TIMEOUT_MS),
        firefox.exited.then((code) => {
          throw new Error(`Firefox exited (code ${code}) before reporting: ${firefox.output.join('').slice(-2000)}`);
        }),
      ]);
      checkResult(result, node);
    } finally {
      await firefox.close();
    }
  }, RESULT_TIMEOUT_MS + 30_000);
});
