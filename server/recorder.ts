// The --record adapter: writes a room's input log with the server/log writer (header, every applied tick record,
// a state hash every N ticks, the end record), and turns write failures into a logged stop instead of a dead room.
import { mkdir } from 'node:fs/promises';
import { join } from 'node:path';
import type { TickInputRecord } from '../shared/sim/types.ts';
import { TICK_RATE_HZ } from '../shared/tick-rate.ts';
import { installedJoltVersion, LogWriter } from './log/index.ts';
import type { Logger } from './logger.ts';
import type { RoomRecorder } from './room.ts';

/** Options of createRoomRecorder. */
export interface RoomRecorderOptions {
  /** Directory the log goes into (created if missing). */
  dir: string;
  roomId: string;
  scenario: string;
  /** Content hash of the scenario's module ('' for a built-in). */
  scenarioHash?: string;
  params: Readonly<Record<string, number>>;
  seed: number | string;
  /** The simulation's tick counter when recording starts (must be 0: a log starts at the first tick). */
  startTick: number;
  /** The initial state hash (tick 0). */
  initialHash: string;
  logger: Logger;
  /** A hash record every N ticks (0: none). Default DEFAULT_LOG_HASH_EVERY_TICKS. */
  hashEveryTicks?: number;
  /** Stamp in file names and the header; default the current time. */
  createdAt?: Date;
  createdBy?: string;
}

/** How often a recording stores the state hash by default: once a second of play (replay checks each one). */
export const DEFAULT_LOG_HASH_EVERY_TICKS = 60;

/** A file name for a room's log: `<roomId>-<UTC timestamp>.taoslog`. */
export function recordingFileName(roomId: string, createdAt: Date): string {
  const stamp = createdAt.toISOString().replace(/[-:]/g, '').replace(/\.\d+Z$/, 'Z');
  return `${roomId}-${stamp}.taoslog`;
}

/** A recorder that writes the room's log to `dir`. */
export async function createRoomRecorder(opts: RoomRecorderOptions): Promise<RoomRecorder & { readonly path: string }> {
  if (opts.startTick !== 0) throw new Error(`room ${opts.roomId}: recording must start at tick 0 (the room is at tick ${opts.startTick})`);
  await mkdir(opts.dir, { recursive: true });
  const createdAt = opts.createdAt ?? new Date();
  let path = join(opts.dir, recordingFileName(opts.roomId, createdAt));
  const hashEvery = opts.hashEveryTicks ?? DEFAULT_LOG_HASH_EVERY_TICKS;
  const header = {
    joltVersion: installedJoltVersion(),
    scenario: opts.scenario,
    scenarioHash: opts.scenarioHash ?? '',
    params: { ...opts.params },
    seed: opts.seed,
    tickRateHz: TICK_RATE_HZ,
    hashEveryTicks: hashEvery,
    checkpointEveryTicks: 0,
    createdBy: opts.createdBy ?? `taos-physics serve (room ${opts.roomId})`,
  };
  let writer: LogWriter;
  try {
    writer = await LogWriter.create(path, header);
  } catch (error) {
    // Two rooms with the same id in one second (a room closed and re-created): add a suffix instead of failing.
    if (!(error instanceof Error) || !/already exists/.test(error.message)) throw error;
    path = path.replace(/\.taoslog$/, `-${process.pid}-${Math.floor(performance.now())}.taoslog`);
    writer = await LogWriter.create(path, header);
  }
  if (hashEvery > 0) writer.appendHash(0, opts.initialHash);
  let failed = false;
  const stop = (error: unknown): void => {
    if (failed) return;
    failed = true;
    opts.logger.error({ room: opts.roomId, path, err: error }, 'recording failed; the room goes on without it');
    void writer.abandon().catch(() => undefined);
  };
  opts.logger.info({ room: opts.roomId, path }, 'recording room');
  return {
    path,
    append(record: TickInputRecord): void {
      if (failed) return;
      try {
        writer.appendTick(record);
      } catch (error) {
        stop(error);
      }
    },
    afterStep(tick: number, hash: () => string): void {
      if (failed || hashEvery === 0 || tick % hashEvery !== 0) return;
      try {
        writer.appendHash(tick, hash());
      } catch (error) {
        stop(error);
      }
    },
    async close(finalTick: number, finalHash: string | null): Promise<void> {
      if (failed) return;
      failed = true;
      if (finalHash === null || finalTick !== writer.ticks) {
        await writer.abandon();
        opts.logger.warn({ room: opts.roomId, path, ticks: writer.ticks }, 'recording closed without an end record');
        return;
      }
      await writer.close(finalTick, finalHash);
      opts.logger.info({ room: opts.roomId, path, ticks: finalTick }, 'recording complete');
    },
  };
}
