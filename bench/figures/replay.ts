// Replay: a 1000-body shape-rain session recorded by the CLI (`record`, a hash every tick), then replayed with the
// replay command's own code (replayLog: read, step, check every hash) against the floor of the same ticks (the bot's
// character update plus the bare Jolt step, summed); whole passes alternate so load drifts hit both.
import { mkdtemp, rm } from 'node:fs/promises';
import { tmpdir } from 'node:os';
import { join } from 'node:path';
import { replayLog } from '../../cli/replay-session.ts';
import { LogReader } from '../../server/log/index.ts';
import { PhysicsWorld } from '../../shared/physics/index.ts';
import type { TickInputRecord } from '../../shared/sim/types.ts';
import { CLI_PATH, runToEnd, startNode } from '../lib/child.ts';
import type { FigureImpl, FigureOutput } from '../lib/figure.ts';
import { floorStepBatch } from '../lib/raw-step.ts';
import { createSceneSim, PILE_SCENE } from '../lib/scenes.ts';
import { alternate, median, ratio, round, sum } from '../lib/stats.ts';

const GOAL = 1.05;
const BATCH_TICKS = 20;

async function readRecords(file: string): Promise<TickInputRecord[]> {
  const reader = await LogReader.open(file);
  const out: TickInputRecord[] = [];
  try {
    for await (const e of reader.entries()) if (e.type === 'tick') out.push(e.record);
  } finally {
    await reader.close();
  }
  return out;
}

/** One floor pass: the log's ticks stepped in batches, each batch first timed as floor ticks, then run for real. */
async function floorPass(records: readonly TickInputRecord[]): Promise<number> {
  const sim = await createSceneSim(PILE_SCENE);
  try {
    let total = 0;
    for (let i = 0; i < records.length; i += BATCH_TICKS) {
      const batch = records.slice(i, i + BATCH_TICKS);
      total += sum(floorStepBatch(sim, batch.length).map((t) => t.ms));
      for (const r of batch) sim.step(r);
    }
    return total;
  } finally {
    sim.destroy();
  }
}

/** One replay pass: wall time of replayLog, with the Jolt steps inside it summed on the side. */
async function replayPass(file: string, ticks: number): Promise<{ wallMs: number; embeddedStepMs: number }> {
  const proto = PhysicsWorld.prototype;
  const original = proto.stepFixed;
  let embedded = 0;
  proto.stepFixed = function timedStep(this: PhysicsWorld) {
    const t0 = performance.now();
    try {
      return original.call(this);
    } finally {
      embedded += performance.now() - t0;
    }
  };
  try {
    const t0 = performance.now();
    const report = await replayLog(file);
    const wallMs = performance.now() - t0;
    if (report.status !== 'ok' || report.ticks !== ticks) throw new Error(`replay: ${report.status} after ${report.ticks} of ${ticks} ticks`);
    return { wallMs, embeddedStepMs: embedded };
  } finally {
    proto.stepFixed = original;
  }
}

async function run(opts: { quick: boolean; log(m: string): void }): Promise<FigureOutput> {
  const ticks = opts.quick ? 300 : 1200;
  const passes = opts.quick ? 1 : 3;
  const dir = await mkdtemp(join(tmpdir(), 'taos-bench-replay-'));
  try {
    const file = join(dir, 'pile.taoslog');
    opts.log(`recording ${ticks} ticks of ${PILE_SCENE.label} with the CLI`);
    const params = Object.entries(PILE_SCENE.params).flatMap(([k, v]) => ['--param', `${k}=${v}`]);
    const out = await runToEnd(startNode(CLI_PATH, ['record', '--scenario', PILE_SCENE.scenario, ...params, '--bots', '1', '--ticks', String(ticks), '--out', file, '--json']), 180_000, 'record');
    const recorded = JSON.parse(out.trim().split('\n').at(-1)!) as { sizeBytes: number; hash: string };
    const records = await readRecords(file);
    if (records.length !== ticks) throw new Error(`replay: the log holds ${records.length} tick records, expected ${ticks}`);
    // Loads Jolt and warms the code paths once, untimed.
    await replayPass(file, ticks);
    const wall: number[] = [];
    const embedded: number[] = [];
    const floor: number[] = [];
    opts.log(`${passes} alternating pair(s) of replay and floor passes over ${ticks} ticks`);
    await alternate(
      passes,
      async () => {
        const r = await replayPass(file, ticks);
        wall.push(r.wallMs);
        embedded.push(r.embeddedStepMs);
      },
      async () => {
        floor.push(await floorPass(records));
      },
    );
    const replayMs = median(wall);
    const floorMs = median(floor);
    const replayRatio = ratio(replayMs, floorMs);
    const embeddedRatio = ratio(replayMs, median(embedded));
    return {
      headline: { replayRatio: replayRatio === null ? null : round(replayRatio, 3) },
      detail: {
        scene: PILE_SCENE,
        ticks,
        bots: 1,
        hashEveryTicks: 1,
        logBytes: recorded.sizeBytes,
        passes,
        replayWallMs: wall.map((v) => round(v, 1)),
        floorSumMs: floor.map((v) => round(v, 1)),
        embeddedStepSumMs: embedded.map((v) => round(v, 1)),
        replayMsPerTick: round(replayMs / ticks, 3),
        floorMsPerTick: round(floorMs / ticks, 3),
        replayOverEmbeddedSteps: embeddedRatio === null ? null : round(embeddedRatio, 3),
      },
      rows: [
        { figure: 'replay', measure: `replay / floor, ${ticks} ticks of ${PILE_SCENE.label} with 1 bot (${(replayMs / 1000).toFixed(1)}/${(floorMs / 1000).toFixed(1)} s)`, value: replayRatio, unit: '×', digits: 3, goal: { op: '<=', value: GOAL } },
        { figure: 'replay', measure: 'replay / Jolt steps inside the replay (cross-check)', value: embeddedRatio, unit: '×', digits: 3 },
      ],
      charts: [
        {
          title: `Replay of ${ticks} ticks of ${PILE_SCENE.label} (ms per tick, median pass)`,
          unit: 'ms per tick',
          bars: [
            { label: 'floor: character update + Jolt step', value: floorMs / ticks, series: 'raw' },
            { label: 'replay (read, step, check hashes)', value: replayMs / ticks, series: 'ours' },
            { label: 'Jolt steps inside the replay', value: median(embedded) / ticks, series: 'other' },
          ],
        },
      ],
      notes: [
        `Recorded with \`taos-physics record --scenario ${PILE_SCENE.scenario} --param count=1000 --bots 1 --ticks ${ticks}\` (a hash record every tick, a checkpoint every 600), ${Math.round(recorded.sizeBytes / 1024)} KiB.`,
        'Replay: wall time of replayLog() (the replay command without printing): builds the scenario, reads every record, steps, compares every hash. Floor: the same ticks as batches from fast checkpoints of the bot character\'s update (its last command, CharacterController.move) plus the bare PhysicsWorld.stepFixed() (bench/lib/raw-step.ts).',
        `${passes} replay and ${passes} floor pass(es), alternating, after one untimed warm-up replay; medians of pass totals.`,
      ],
    };
  } finally {
    await rm(dir, { recursive: true, force: true });
  }
}

/** The replay figure. */
export const figure: FigureImpl = { run };
