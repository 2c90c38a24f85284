// serve --resume DIR: every interrupted recording in DIR is checked (server/log/resume-point.ts), re-simulated from
// its last checkpoint to its last durable tick with every recorded hash compared, and its room reopened under the same
// id at that tick, appending to the same log; its players are held for their clients to come back with their resume
// tokens (keys kept beside the log). A log that fails any check is reported by name and record and left untouched.
import { copyFile, readdir } from 'node:fs/promises';
import { join } from 'node:path';
import { NEUTRAL_INPUT, type InputCommand } from '../shared/sim/input.ts';
import { RecordDeltaCoder, type PlayerInputState } from '../shared/protocol/record-delta.ts';
import type { Simulation } from '../shared/sim/simulation.ts';
import type { GameServer } from './game-server.ts';
import { appendResumeKey, readResumeKeys } from './log/resume-keys.ts';
import { findResumePoint, type ResumePoint } from './log/resume-point.ts';
import type { Logger } from './logger.ts';
import type { RecordingFactory } from './room-factory.ts';
import type { RoomSimulationBuild } from './room-manager.ts';

/**
 * Keeps a resume token's key beside the room's log (synced before the welcome carrying the token leaves), so that the
 * player can come back after a crash; a room that does not record (null path) keeps nothing.
 */
export function rememberResumeKey(logPath: string | null, roomId: string, playerId: number, key: string, logger: Logger): void {
  if (logPath === null) return;
  try {
    appendResumeKey(logPath, playerId, key);
  } catch (error) {
    logger.error({ room: roomId, path: logPath, playerId, err: error }, 'cannot keep a resume key beside the recording: after a restart this player cannot come back');
  }
}

/** Room ids in recording file names: `<roomId>-<UTC stamp>[-<pid>-<n>].taoslog` (server/recorder.ts). */
const LOG_NAME_RE = /^([A-Za-z0-9_-]{1,64})-(\d{8}T\d{6}Z)(?:-\d+-\d+)?\.taoslog$/;

/** A room ready to reopen: its simulation at the resume tick and what the room needs around it. */
export interface ResumedRoom {
  id: string;
  path: string;
  scenario: string;
  seed: number | string;
  built: RoomSimulationBuild & { sim: Simulation };
  point: ResumePoint;
  /** The players in the world at the resume tick, held for a reconnect. */
  players: Array<{ playerId: number; name: string; last: InputCommand }>;
  /** Each held player's resume key (from `<log>.resume`). */
  keys: Map<number, string>;
  tick: number;
  hash: string;
  /** Predict mode's record-coder state at the resume tick (null: the room serves snapshots). */
  predictInputs: PlayerInputState[] | null;
  /** Ticks re-simulated (from the checkpoint, or 0) and how long the whole resume of this log took. */
  resimulatedTicks: number;
  resumeMs: number;
}

/** A log not resumed: why, and where in the file when a record is to blame. */
export interface RefusedLog {
  path: string;
  reason: string;
  recordIndex?: number;
  byteOffset?: number;
}

/** What a resume found in DIR. */
export interface ResumeScan {
  rooms: ResumedRoom[];
  refused: RefusedLog[];
  /** Logs that ended cleanly (nothing to resume). */
  complete: string[];
}

class Refusal extends Error {
  readonly recordIndex?: number;
  readonly byteOffset?: number;
  constructor(message: string, at?: { index: number; offset?: number }) {
    super(message);
    this.recordIndex = at?.index;
    this.byteOffset = at?.offset;
  }
}

/** Re-simulates a resume point into a fresh simulation of its scenario; throws Refusal when anything disagrees. */
async function resimulate(point: ResumePoint, factory: RecordingFactory): Promise<RoomSimulationBuild & { sim: Simulation }> {
  const h = point.header;
  let built;
  try {
    built = await factory.createSimulation(h.scenario, h.params, h.seed);
  } catch (err) {
    throw new Refusal(`its scenario cannot be built: ${(err as Error).message}`, { index: 0 });
  }
  const sim = built.sim;
  try {
    const check = (): void => {
      const recorded = point.hashes.get(sim.tick);
      if (recorded && recorded.hash !== sim.stateHash()) {
        throw new Refusal(`re-simulation disagrees with hash record #${recorded.index} (byte offset ${recorded.offset}) at tick ${sim.tick}: recorded ${recorded.hash}, computed ${sim.stateHash()}`, { index: recorded.index, offset: recorded.offset });
      }
    };
    if (point.checkpoint) {
      try {
        sim.restoreCheckpointBytes(point.checkpoint.bytes);
      } catch (err) {
        throw new Refusal(`checkpoint record #${point.checkpoint.index} at tick ${point.checkpoint.tick} cannot be restored: ${(err as Error).message}`, { index: point.checkpoint.index });
      }
    }
    check();
    for (const record of point.records) {
      try {
        sim.step(record);
      } catch (err) {
        throw new Refusal(`tick record ${record.tick} cannot be applied: ${(err as Error).message}`);
      }
      check();
    }
    if (sim.tick !== point.ticks) throw new Refusal(`re-simulation ended at tick ${sim.tick}, the log holds ${point.ticks} ticks`);
    return built;
  } catch (err) {
    sim.destroy();
    throw err;
  }
}

/** The held players at the end of a resume point: who is in the world, their names and last commands. */
function heldPlayers(point: ResumePoint, sim: Simulation): ResumedRoom['players'] {
  const last = new Map<number, InputCommand>();
  for (const r of point.records) for (const c of r.commands) last.set(c.playerId, c.input);
  return sim.playerIds().map((playerId) => ({ playerId, name: point.names.get(playerId) ?? `player ${playerId}`, last: last.get(playerId) ?? NEUTRAL_INPUT }));
}

/** Checks and re-simulates every interrupted log in `dir` (the newest per room id); opens nothing yet. */
export async function scanForResume(dir: string, factory: RecordingFactory, logger: Logger): Promise<ResumeScan> {
  const scan: ResumeScan = { rooms: [], refused: [], complete: [] };
  let names: string[];
  try {
    names = (await readdir(dir)).filter((n) => n.endsWith('.taoslog')).sort();
  } catch (err) {
    // The first start of a server that always runs with --resume: nothing recorded yet, nothing to resume.
    if ((err as NodeJS.ErrnoException).code === 'ENOENT') return scan;
    throw new Error(`cannot read the --resume directory ${dir}: ${(err as Error).message}`, { cause: err });
  }
  const newest = new Map<string, string>();
  for (const name of names) {
    const m = LOG_NAME_RE.exec(name);
    if (m) newest.set(m[1], name); // sorted by stamp within an id: the last one wins
  }
  for (const name of names) {
    const path = join(dir, name);
    const started = performance.now();
    const m = LOG_NAME_RE.exec(name);
    // Every record goes through a record coder, as a predict-mode room's feed sent it, so the feed can go on.
    let coder: RecordDeltaCoder | null = new RecordDeltaCoder();
    const found = await findResumePoint(path, (record) => {
      try {
        coder?.encode(record);
      } catch {
        coder = null;
      }
    });
    if ('kind' in found) {
      if (found.kind === 'complete') scan.complete.push(path);
      else scan.refused.push({ path, reason: found.reason, recordIndex: found.recordIndex, byteOffset: found.byteOffset });
      continue;
    }
    if (!m) {
      scan.refused.push({ path, reason: 'its name does not say which room it recorded (<room>-<UTC stamp>.taoslog)' });
      continue;
    }
    if (newest.get(m[1]) !== name) {
      scan.refused.push({ path, reason: `a newer log of room ${m[1]} (${newest.get(m[1])}) is the one resumed` });
      continue;
    }
    try {
      const built = await resimulate(found, factory);
      scan.rooms.push({
        id: m[1],
        path,
        scenario: found.header.scenario,
        seed: found.header.seed,
        built,
        point: found,
        players: heldPlayers(found, built.sim),
        keys: readResumeKeys(path),
        predictInputs: coder?.state() ?? null,
        tick: built.sim.tick,
        hash: built.sim.stateHash(),
        resimulatedTicks: found.records.length,
        resumeMs: performance.now() - started,
      });
    } catch (err) {
      if (!(err instanceof Refusal)) throw err;
      scan.refused.push({ path, reason: err.message, recordIndex: err.recordIndex, byteOffset: err.byteOffset });
    }
  }
  for (const r of scan.refused) logger.error({ path: r.path, recordIndex: r.recordIndex, byteOffset: r.byteOffset, reason: r.reason }, 'not resuming this log (left untouched)');
  return scan;
}

/**
 * Reopens the scanned rooms in the server: each log goes on (a damaged or partial tail is first copied to
 * `<log>.tail-<offset>` and cut off), the room opens under its id at the resume tick, and its players are held for
 * the grace window, or leave on the first tick when they cannot come back (no key, or reconnects are off).
 */
export async function reopenRooms(server: GameServer, scan: ResumeScan, factory: RecordingFactory, logger: Logger): Promise<void> {
  for (const r of scan.rooms) {
    const p = r.point;
    try {
      if (p.validBytes < p.fileBytes) await copyFile(r.path, `${r.path}.tail-${p.validBytes}`);
      const recording = await factory.continueRecording(
        { id: r.id, scenario: r.scenario, params: r.built.params, seed: r.seed, sim: r.built.sim },
        { path: r.path, header: p.header, ticks: p.ticks, validBytes: p.validBytes },
      );
      const spec = { id: r.id, scenario: r.scenario, params: r.built.params, seed: r.seed };
      const room = server.rooms.adopt(spec, r.built, recording, (room) => room.restorePlayers(r.players, Math.max(p.maxPlayerId, ...r.players.map((x) => x.playerId))), r.predictInputs);
      const resume = server.access.resume;
      for (const player of r.players) {
        const key = r.keys.get(player.playerId);
        if (resume && key) resume.adopt(room, player.playerId, key);
        else room.leave(player.playerId);
      }
      logger.info({ room: r.id, path: r.path, tick: r.tick, hash: r.hash, ending: p.ending, tailDamage: p.tailDamage, fromCheckpoint: p.checkpoint?.tick ?? null, resimulatedTicks: r.resimulatedTicks, resumeMs: Math.round(r.resumeMs), heldPlayers: r.players.length }, 'room resumed');
    } catch (err) {
      r.built.sim.destroy();
      scan.refused.push({ path: r.path, reason: `cannot reopen: ${(err as Error).message}` });
      logger.error({ room: r.id, path: r.path, err }, 'cannot reopen a resumed room');
    }
  }
}
