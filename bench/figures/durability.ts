// Durability cost: a recorded character-course room (4 bots, a hash every 60 ticks, a checkpoint every 10 s) paced
// at 60 Hz through the server's recorder in each --durability mode, batches alternating between modes. Per tick it
// times the recorder's work on the tick thread plus, in tick mode, the wait until the tick's record is fdatasynced
// and its results may go out: how much later a client sees each tick because of the mode.
import { mkdtemp, readFile, rm } from 'node:fs/promises';
import { tmpdir } from 'node:os';
import { join } from 'node:path';
import { readLogBytes } from '../../server/log/index.ts';
import { silentLogger } from '../../server/logger.ts';
import { createRoomRecorder, DURABILITY_MODES, type DurabilityMode } from '../../server/recorder.ts';
import { TICK_MS, TICK_RATE_HZ } from '../../shared/tick-rate.ts';
import type { FigureImpl, FigureOutput, ReportRow } from '../lib/figure.ts';
import { botRecords, createSceneSim } from '../lib/scenes.ts';
import { quantile, round } from '../lib/stats.ts';

const SCENE = { scenario: 'character-course', params: {}, label: 'character-course' } as const;
const BOTS = 4;
const CHECKPOINT_EVERY_TICKS = 600;

interface Batch {
  costMs: number[];
  /** Log bytes a minute of this play takes: tick and hash records as recorded, checkpoints at their period. */
  bytesPerMinute: number;
  syncs: number;
}

/** A minute of the log: its tick and hash records scaled to 3600 ticks plus a checkpoint every CHECKPOINT_EVERY_TICKS. */
async function bytesPerMinute(path: string): Promise<number> {
  const log = readLogBytes(new Uint8Array(await readFile(path)));
  let streamBytes = 0;
  const checkpoints: number[] = [];
  for (const e of log.entries) {
    if (e.type === 'tick' || e.type === 'hash') streamBytes += e.sizeBytes;
    else if (e.type === 'checkpoint') checkpoints.push(e.sizeBytes);
  }
  const minuteTicks = TICK_RATE_HZ * 60;
  const checkpointBytes = checkpoints.length > 0 ? checkpoints.reduce((a, b) => a + b, 0) / checkpoints.length : 0;
  return Math.round((streamBytes / log.outcome.ticks) * minuteTicks + checkpointBytes * (minuteTicks / CHECKPOINT_EVERY_TICKS));
}

const sleep = (ms: number): Promise<void> => new Promise((done) => setTimeout(done, Math.max(0, ms)));

/** One paced batch of `ticks` ticks in `mode`, each tick's cost = recorder work + wait for its release. */
async function batch(mode: DurabilityMode, ticks: number, dir: string, index: number): Promise<Batch> {
  const sim = await createSceneSim(SCENE);
  const bots = botRecords(BOTS);
  const rec = await createRoomRecorder({
    dir,
    roomId: `${mode}-${index}`,
    scenario: SCENE.scenario,
    params: sim.params,
    seed: sim.seed,
    startTick: 0,
    initialHash: sim.stateHash(),
    logger: silentLogger(),
    durability: { mode },
    checkpointEveryTicks: CHECKPOINT_EVERY_TICKS,
    checkpoint: () => sim.saveCheckpointBytes(),
  });
  const costMs: number[] = [];
  try {
    const start = performance.now();
    for (let t = 0; t < ticks; t++) {
      await sleep(start + t * TICK_MS - performance.now());
      const record = bots.next();
      const t0 = performance.now();
      rec.append(record);
      let stepMs = performance.now();
      sim.step(record);
      stepMs = performance.now() - stepMs;
      rec.afterStep(sim.tick, () => sim.stateHash());
      const released = new Promise<number>((done) => (rec.release ? rec.release(t, () => done(performance.now())) : done(performance.now())));
      costMs.push((await released) - t0 - stepMs);
    }
    await rec.close(sim.tick, sim.stateHash());
    return { costMs, bytesPerMinute: await bytesPerMinute(rec.path), syncs: rec.syncs };
  } finally {
    sim.destroy();
  }
}

async function run(opts: { quick: boolean; log(m: string): void }): Promise<FigureOutput> {
  const ticks = opts.quick ? 240 : 900;
  const rounds = opts.quick ? 2 : 3;
  const dir = await mkdtemp(join(tmpdir(), 'taos-bench-durability-'));
  const byMode = new Map<DurabilityMode, Batch[]>(DURABILITY_MODES.map((m) => [m, []]));
  try {
    for (let r = 0; r < rounds; r++) {
      // Alternating order (tick interval off, off interval tick, …) so load drifts hit every mode.
      const order = r % 2 === 0 ? [...DURABILITY_MODES] : [...DURABILITY_MODES].reverse();
      for (const mode of order) {
        opts.log(`round ${r + 1}/${rounds}: ${ticks} ticks at ${TICK_RATE_HZ} Hz with --durability ${mode}`);
        byMode.get(mode)!.push(await batch(mode, ticks, dir, r));
      }
    }
  } finally {
    await rm(dir, { recursive: true, force: true });
  }
  const detail: Record<string, unknown> = { scene: SCENE.label, bots: BOTS, ticksPerBatch: ticks, rounds, checkpointEveryTicks: CHECKPOINT_EVERY_TICKS };
  const headline: Record<string, number | null> = {};
  const rows: ReportRow[] = [];
  const bars = [];
  for (const mode of DURABILITY_MODES) {
    const batches = byMode.get(mode)!;
    const all = batches.flatMap((b) => b.costMs);
    const p50 = round(quantile(all, 0.5), 3);
    const p99 = round(quantile(all, 0.99), 3);
    const logBytesPerMinute = batches[0].bytesPerMinute;
    const syncsPerTick = round(batches.reduce((n, b) => n + b.syncs, 0) / (batches.length * ticks), 3);
    detail[mode] = { p50Ms: p50, p99Ms: p99, maxMs: round(Math.max(...all), 3), syncsPerTick, logBytesPerMinute };
    const key = mode[0].toUpperCase() + mode.slice(1);
    headline[`durability${key}P50Ms`] = p50;
    headline[`durability${key}P99Ms`] = p99;
    rows.push({ figure: 'durability', measure: `--durability ${mode}: per-tick cost p50 (recorder + wait for release)`, value: p50, unit: 'ms', digits: 3 });
    rows.push({ figure: 'durability', measure: `--durability ${mode}: per-tick cost p99`, value: p99, unit: 'ms', digits: 3 });
    bars.push({ label: `${mode} p50`, value: p50, series: mode === 'tick' ? ('ours' as const) : ('other' as const) }, { label: `${mode} p99`, value: p99, series: mode === 'tick' ? ('ours' as const) : ('other' as const) });
  }
  const tickMode = detail.tick as { logBytesPerMinute: number };
  headline.logBytesPerMinute = tickMode.logBytesPerMinute;
  rows.push({ figure: 'durability', measure: `log size per minute, ${BOTS} bots, checkpoint every ${CHECKPOINT_EVERY_TICKS / TICK_RATE_HZ} s`, value: tickMode.logBytesPerMinute / 1024, unit: 'KiB', digits: 1 });
  return {
    headline,
    detail,
    rows,
    charts: [{ title: `Per-tick durability cost, ${SCENE.label} with ${BOTS} bots (ms)`, unit: 'ms', bars }],
    notes: [
      `Each batch: a fresh ${SCENE.label} room with ${BOTS} bots recorded through server/recorder.ts, paced at ${TICK_RATE_HZ} Hz; ${rounds} rounds, modes alternating. Cost per tick: the recorder's work on the tick thread (append, hash, checkpoint) plus, in tick mode, the wait until the group commit's fdatasync covers the tick (its snapshot and events are held that long). The step itself is not counted.`,
      'The log lives in the OS temp directory: the figure is only as good as that disk\'s fdatasync.',
    ],
  };
}

/** The durability figure. */
export const figure: FigureImpl = { run };
