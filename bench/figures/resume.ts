// Resume time: a character-course session with 4 bots (10 minutes; 2 in a quick run) recorded twice, with a
// checkpoint every 10 s and with none, each left without its end record as a crash leaves it; then the time
// `serve --resume` spends on it (server/resume-rooms.ts: read and check every record, restore the last checkpoint,
// re-simulate to the last tick, compare the hashes), the two logs alternating.
import { mkdir, mkdtemp, readFile, rm, writeFile } from 'node:fs/promises';
import { tmpdir } from 'node:os';
import { join } from 'node:path';
import { readLogBytes } from '../../server/log/index.ts';
import { SessionLog } from '../../server/log/session-log.ts';
import { silentLogger } from '../../server/logger.ts';
import { scanForResume } from '../../server/resume-rooms.ts';
import { createRoomFactory } from '../../server/room-factory.ts';
import { registryScenarios } from '../../server/start-server.ts';
import { TICK_RATE_HZ } from '../../shared/tick-rate.ts';
import type { FigureImpl, FigureOutput } from '../lib/figure.ts';
import { botRecords, createSceneSim } from '../lib/scenes.ts';
import { alternate, median, round } from '../lib/stats.ts';

const SCENE = { scenario: 'character-course', params: {}, label: 'character-course' } as const;
const BOTS = 4;
const CHECKPOINT_EVERY_TICKS = 600;
const GOAL_MS = 1000;

/** Records `ticks` ticks into DIR/default-….taoslog and cuts off the end record; returns the file size. */
async function recordCrashed(dir: string, ticks: number, checkpointEveryTicks: number): Promise<number> {
  await mkdir(dir, { recursive: true });
  const path = join(dir, 'default-20260101T000000Z.taoslog');
  const sim = await createSceneSim(SCENE);
  try {
    const log = await SessionLog.create(path, sim, { hashEveryTicks: 60, checkpointEveryTicks, createdBy: 'bench resume' });
    const bots = botRecords(BOTS);
    for (let t = 0; t < ticks; t++) {
      log.step(bots.next());
      if (t % 600 === 599) await log.writer.settled();
    }
    await log.close();
  } finally {
    sim.destroy();
  }
  const bytes = new Uint8Array(await readFile(path));
  const cut = bytes.subarray(0, readLogBytes(bytes).entries.at(-1)!.offset);
  await writeFile(path, cut);
  return cut.length;
}

/** One resume of DIR, timed; the rebuilt simulations are freed. */
async function resumeOnce(dir: string, expectTick: number): Promise<number> {
  const factory = createRoomFactory({ scenarios: registryScenarios(), logger: silentLogger() });
  const t0 = performance.now();
  const scan = await scanForResume(dir, factory, silentLogger());
  const ms = performance.now() - t0;
  for (const r of scan.rooms) r.built.sim.destroy();
  if (scan.rooms.length !== 1 || scan.rooms[0].tick !== expectTick) throw new Error(`resume: expected one room at tick ${expectTick}, got ${JSON.stringify(scan.refused)}`);
  return ms;
}

async function run(opts: { quick: boolean; log(m: string): void }): Promise<FigureOutput> {
  const minutes = opts.quick ? 2 : 10;
  const ticks = minutes * 60 * TICK_RATE_HZ;
  const passes = opts.quick ? 2 : 3;
  const root = await mkdtemp(join(tmpdir(), 'taos-bench-resume-'));
  try {
    opts.log(`recording ${minutes} min of ${SCENE.label} with ${BOTS} bots, with and without checkpoints`);
    const withDir = join(root, 'with');
    const withoutDir = join(root, 'without');
    const withBytes = await recordCrashed(withDir, ticks, CHECKPOINT_EVERY_TICKS);
    const withoutBytes = await recordCrashed(withoutDir, ticks, 0);
    await resumeOnce(withDir, ticks); // loads Jolt and warms the code, untimed
    const withMs: number[] = [];
    const withoutMs: number[] = [];
    opts.log(`${passes} alternating pair(s) of resumes`);
    await alternate(
      passes,
      async () => void withMs.push(await resumeOnce(withDir, ticks)),
      async () => void withoutMs.push(await resumeOnce(withoutDir, ticks)),
    );
    const withMedian = round(median(withMs), 1);
    const withoutMedian = round(median(withoutMs), 1);
    return {
      headline: { resumeMsCheckpoints: withMedian, resumeMsNoCheckpoints: withoutMedian },
      detail: { scene: SCENE.label, bots: BOTS, minutes, ticks, checkpointEveryTicks: CHECKPOINT_EVERY_TICKS, withCheckpointsMs: withMs.map((v) => round(v, 1)), withoutCheckpointsMs: withoutMs.map((v) => round(v, 1)), withCheckpointsBytes: withBytes, withoutCheckpointsBytes: withoutBytes },
      rows: [
        { figure: 'resume', measure: `resume a ${minutes}-min crashed session, checkpoint every ${CHECKPOINT_EVERY_TICKS / TICK_RATE_HZ} s`, value: withMedian, unit: 'ms', digits: 1, goal: { op: '<=', value: GOAL_MS } },
        { figure: 'resume', measure: `resume a ${minutes}-min crashed session, no checkpoints (replay from tick 0)`, value: withoutMedian, unit: 'ms', digits: 1 },
      ],
      charts: [
        {
          title: `Resume of a ${minutes}-minute crashed session (ms)`,
          unit: 'ms',
          goal: GOAL_MS,
          bars: [
            { label: 'with checkpoints', value: withMedian, series: 'ours' },
            { label: 'without (from tick 0)', value: withoutMedian, series: 'baseline' },
          ],
        },
      ],
      notes: [
        `Each log: ${minutes} min of ${SCENE.label} with ${BOTS} scripted bots (a hash every 60 ticks), end record removed; ${Math.round(withBytes / 1024)} KiB with checkpoints, ${Math.round(withoutBytes / 1024)} KiB without.`,
        'Timed: scanForResume() on a directory holding only that log: read it, check every record, build the scenario, restore the last checkpoint, re-simulate to the last tick comparing hashes. Opening the room and the socket work are not included.',
      ],
    };
  } finally {
    await rm(root, { recursive: true, force: true });
  }
}

/** The resume figure. */
export const figure: FigureImpl = { run };
