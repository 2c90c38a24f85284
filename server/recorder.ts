// The --record adapter: writes a room's input log with the server/log writer (header, every applied tick record,
// a state hash every N ticks, a checkpoint every C ticks, the end record) under a durability policy (--durability),
// and turns write failures into a logged stop instead of a dead room.
import { mkdir } from 'node:fs/promises';
import { join } from 'node:path';
import type { TickInputRecord } from '../shared/sim/types.ts';
import { TICK_RATE_HZ } from '../shared/tick-rate.ts';
import { GroupCommit } from './log/group-commit.ts';
import { installedJoltVersion, LogWriter, type LogHeaderInit } from './log/index.ts';
import type { Logger } from './logger.ts';
import type { RoomRecorder } from './room.ts';

/**
 * When a recording's records reach the disk. tick: a tick's record is written and fdatasynced (group commit)
 * before its snapshot, events or input acks leave the server, so nothing a client saw can be lost; interval: a
 * write + fdatasync every DurabilityOptions.intervalMs, clients are not held back, a crash loses at most that much;
 * off: records reach the OS every second and the disk at checkpoints and close.
 */
export const DURABILITY_MODES = ['tick', 'interval', 'off'] as const;
export type DurabilityMode = (typeof DURABILITY_MODES)[number];
/** The default: what a client saw is on disk, for well under a millisecond a tick (docs/server.md, "Durability"). */
export const DEFAULT_DURABILITY: DurabilityMode = 'tick';
/** The interval mode's sync period by default: a crash loses at most this much play (plus one sync). */
export const DEFAULT_DURABILITY_INTERVAL_MS = 250;
/** Checkpoints in server recordings by default: every 10 s of play (resume and replay --from start there). */
export const DEFAULT_CHECKPOINT_EVERY_SECONDS = 10;

/** A recording's durability policy. */
export interface DurabilityOptions {
  mode: DurabilityMode;
  /** Sync period of the interval mode (ms). */
  intervalMs?: number;
}

/** Where a resumed room's log goes on: its file, header and the point after its last whole record. */
export interface ContinuedLog {
  path: string;
  header: LogHeaderInit;
  ticks: number;
  validBytes: number;
}

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
  /** Default { mode: DEFAULT_DURABILITY }. */
  durability?: DurabilityOptions;
  /** A checkpoint record every C ticks (0: none; needs `checkpoint`). Default 0. */
  checkpointEveryTicks?: number;
  /** The simulation's byte checkpoint, taken after a step. */
  checkpoint?: () => Uint8Array;
  /** Go on appending to this log (a resumed room) instead of creating one. */
  continueLog?: ContinuedLog;
  /** Called once when the recording closes or fails. */
  onClose?: () => void;
}

/** A running recording: the room's recorder plus what the server reports about it. */
export interface RoomRecording extends RoomRecorder {
  readonly path: string;
  readonly durability: DurabilityMode;
  /** Writes + fdatasyncs issued for durability (tick and interval modes). */
  readonly syncs: number;
}

async function openWriter(opts: RoomRecorderOptions, mode: DurabilityMode): Promise<{ writer: LogWriter; path: string; fresh: boolean }> {
  // In tick mode the group commit writes; interval and off hand records to the OS every second as before.
  const writerOpts = mode === 'tick' ? { flushEveryTicks: 0xffffffff } : {};
  if (opts.continueLog) {
    const c = opts.continueLog;
    return { writer: await LogWriter.continue(c.path, c.header, c, writerOpts), path: c.path, fresh: false };
  }
  await mkdir(opts.dir, { recursive: true });
  const createdAt = opts.createdAt ?? new Date();
  let path = join(opts.dir, recordingFileName(opts.roomId, createdAt));
  const header: LogHeaderInit = {
    joltVersion: installedJoltVersion(),
    scenario: opts.scenario,
    scenarioHash: opts.scenarioHash ?? '',
    params: { ...opts.params },
    seed: opts.seed,
    tickRateHz: TICK_RATE_HZ,
    hashEveryTicks: opts.hashEveryTicks ?? DEFAULT_LOG_HASH_EVERY_TICKS,
    checkpointEveryTicks: opts.checkpoint ? (opts.checkpointEveryTicks ?? 0) : 0,
    createdBy: opts.createdBy ?? `taos-physics serve (room ${opts.roomId})`,
  };
  try {
    return { writer: await LogWriter.create(path, header, writerOpts), path, fresh: true };
  } catch (error) {
    // Two rooms with the same id in one second (a room closed and re-created): add a suffix instead of failing.
    if (!(error instanceof Error) || !/already exists/.test(error.message)) throw error;
    path = path.replace(/\.taoslog$/, `-${process.pid}-${Math.floor(performance.now())}.taoslog`);
    return { writer: await LogWriter.create(path, header, writerOpts), path, fresh: true };
  }
}

/** How often a recording stores the state hash by default: once a second of play (replay checks each one). */
export const DEFAULT_LOG_HASH_EVERY_TICKS = 60;

/** A file name for a room's log: `<roomId>-<UTC timestamp>.taoslog`. */
export function recordingFileName(roomId: string, createdAt: Date): string {
  const stamp = createdAt.toISOString().replace(/[-:]/g, '').replace(/\.\d+Z$/, 'Z');
  return `${roomId}-${stamp}.taoslog`;
}

/** A recorder that writes the room's log to `dir` (or goes on with opts.continueLog). */
export async function createRoomRecorder(opts: RoomRecorderOptions): Promise<RoomRecording> {
  const durability = opts.durability ?? { mode: DEFAULT_DURABILITY };
  const mode = durability.mode;
  if (!DURABILITY_MODES.includes(mode)) throw new Error(`durability must be one of ${DURABILITY_MODES.join(', ')}, got ${String(mode)}`);
  const expectedTick = opts.continueLog ? opts.continueLog.ticks : 0;
  if (opts.startTick !== expectedTick) throw new Error(`room ${opts.roomId}: recording must start at tick ${expectedTick} (the room is at tick ${opts.startTick})`);
  const { writer, path, fresh } = await openWriter(opts, mode);
  const hashEvery = writer.header.hashEveryTicks;
  const checkpointEvery = opts.checkpoint ? writer.header.checkpointEveryTicks : 0;
  if (fresh && hashEvery > 0) writer.appendHash(0, opts.initialHash);
  let failed = false;
  let syncs = 0;
  let timer: NodeJS.Timeout | null = null;
  const stop = (error: unknown): void => {
    if (failed) return;
    failed = true;
    opts.onClose?.();
    if (timer) clearInterval(timer);
    opts.logger.error({ room: opts.roomId, path, err: error }, 'recording failed; the room goes on without it');
    void writer.abandon().catch(() => undefined);
  };
  const commit = mode === 'tick' ? new GroupCommit(writer, stop) : null;
  if (mode === 'interval') {
    const intervalMs = durability.intervalMs ?? DEFAULT_DURABILITY_INTERVAL_MS;
    if (!Number.isInteger(intervalMs) || intervalMs < 1) throw new Error(`the durability interval must be a positive whole number of ms, got ${intervalMs}`);
    let syncedBytes = writer.bytesAppended;
    let syncing = false;
    timer = setInterval(() => {
      if (failed || syncing || writer.bytesAppended === syncedBytes) return;
      syncing = true;
      const target = writer.bytesAppended;
      syncs++;
      writer.sync().then(
        () => {
          syncing = false;
          syncedBytes = target;
        },
        (error: unknown) => stop(error),
      );
    }, intervalMs);
    timer.unref();
  }
  opts.logger.info({ room: opts.roomId, path, durability: mode, resumedAtTick: opts.continueLog?.ticks }, opts.continueLog ? 'recording resumed room' : 'recording room');
  const recording: RoomRecording = {
    path,
    durability: mode,
    get syncs(): number {
      return syncs + (commit?.syncs ?? 0);
    },
    append(record: TickInputRecord): void {
      if (failed) return;
      try {
        writer.appendTick(record);
      } catch (error) {
        stop(error);
      }
    },
    afterStep(tick: number, hash: () => string): void {
      if (failed) return;
      try {
        if (hashEvery > 0 && tick % hashEvery === 0) writer.appendHash(tick, hash());
        if (checkpointEvery > 0 && tick % checkpointEvery === 0 && opts.checkpoint) writer.appendCheckpoint(tick, opts.checkpoint());
      } catch (error) {
        stop(error);
      }
    },
    async handOff(): Promise<ContinuedLog | null> {
      if (failed) return null;
      failed = true; // nothing more is appended on this thread
      if (timer) clearInterval(timer);
      try {
        // Every record durable and every send held for one released (in order) before another thread takes the file.
        if (commit) await new Promise<void>((resolve) => commit.whenDurable(resolve));
        else await writer.sync();
        await writer.abandon();
      } catch (error) {
        failed = false;
        stop(error);
        return null;
      } finally {
        opts.onClose?.();
      }
      opts.logger.info({ room: opts.roomId, path, ticks: writer.ticks }, 'recording handed to another thread');
      return { path, header: writer.header, ticks: writer.ticks, validBytes: writer.bytesAppended };
    },
    async close(finalTick: number, finalHash: string | null): Promise<void> {
      if (failed) return;
      failed = true;
      opts.onClose?.();
      if (timer) clearInterval(timer);
      commit?.clear();
      if (finalHash === null || finalTick !== writer.ticks) {
        await writer.abandon();
        opts.logger.warn({ room: opts.roomId, path, ticks: writer.ticks }, 'recording closed without an end record');
        return;
      }
      // A final checkpoint, so a replay of the session's end (replay --from) starts next to it.
      if (checkpointEvery > 0 && finalTick % checkpointEvery !== 0 && opts.checkpoint) writer.appendCheckpoint(finalTick, opts.checkpoint());
      await writer.close(finalTick, finalHash);
      opts.logger.info({ room: opts.roomId, path, ticks: finalTick }, 'recording complete');
    },
  };
  if (commit) recording.release = (_tick: number, send: () => void): void => (failed ? send() : commit.whenDurable(send));
  return recording;
}
