// Re-simulates an input log: rebuilds the scenario from the header, applies every tick record, checks every
// recorded hash, and on the first mismatch names the divergent tick and (from the next recorded checkpoint) the
// first differing body. Shared by `replay`, `verify` and its worker threads; prints nothing.
import { stat } from 'node:fs/promises';
import type { Divergence } from '../shared/sim/state-dump.ts';
import type { Simulation } from '../shared/sim/simulation.ts';
import { installedJoltVersion } from '../server/log/jolt-version.ts';
import { LogCorruptError, type LogEntry, type LogHeader, type LogStatus } from '../server/log/log-format.ts';
import { LogReader } from '../server/log/log-reader.ts';
import { scenarioNames } from '../scenarios/index.ts';
import { scenarioModuleHash, shortHash } from '../server/scenario-module.ts';
import type { ScenarioDefinition } from '../shared/sim/scenario.ts';
import { createSimulation, scenarioNamed } from './scenario-setup.ts';

/** A log cannot be replayed with the scenario at hand (not built in, another name, another module version). */
export class ScenarioVersionError extends Error {
  override name = 'ScenarioVersionError';
}

/** What to replay and what to keep. */
export interface ReplayOptions {
  /** The scenario to replay with (a loaded module); default the built-in scenario the log names. */
  scenario?: ScenarioDefinition;
  /** Replay even when the scenario's module hash differs from the one the log was recorded with. */
  force?: boolean;
  /** Stop once the simulation's tick counter reaches this (default: the whole log). */
  toTick?: number;
  /** Start from the last recorded checkpoint at or before this tick counter instead of tick 0 (none: from 0). */
  fromTick?: number;
  /** Keep the state hash at every tick counter 0…n (for verify). */
  collectHashes?: boolean;
  /** Called now and then with the fraction of the file read and the tick counter. */
  onProgress?: (fraction: number, tick: number) => void;
}

/** Where the replay first disagreed with the log. */
export interface ReplayDivergence {
  /** Tick counter of the first mismatching hash (after applying tick record tick − 1). */
  tick: number;
  expected: string;
  actual: string;
  /** The hash (or end) record that disagreed. */
  recordIndex: number;
  byteOffset: number;
  /** The first difference against the first recorded checkpoint at or after `tick`, if the log has one;
   *  `body` says what the differing body is (e.g. "player 3's character", "dynamic box"). */
  state: (Divergence & { checkpointTick: number; body?: string }) | null;
  /** Why `state` is null, when it is. */
  stateNote?: string;
}

/** The outcome of a replay. */
export interface ReplayReport {
  file: string;
  header: LogHeader;
  /** ok: every recorded hash matched; diverged: see divergence; corrupt: see corruption (the prefix matched). */
  status: 'ok' | 'diverged' | 'corrupt';
  /** How the log itself ended (complete, unterminated, truncated, corrupt), or 'stopped' when the replay stopped
   *  before its end (--to, or a divergence). */
  log: LogStatus | 'stopped';
  /** Tick records applied. */
  ticks: number;
  /** Recorded hashes compared (end record included). */
  hashesChecked: number;
  finalHash: string;
  /** Mean simulation time per applied tick (ms). */
  msPerTick: number;
  /** Bytes of the file past the last whole record, when truncated. */
  droppedBytes: number;
  divergence?: ReplayDivergence;
  corruption?: { recordIndex: number; byteOffset: number; reason: string };
  /** Set when the log was recorded with another jolt-physics version. */
  joltVersionNote?: string;
  /** Set when --force replayed a log recorded with another version of the scenario's module. */
  scenarioNote?: string;
  /** State hash at tick counter 0…ticks (collectHashes only). */
  hashes?: string[];
  /** The tick counter the replay started at (a checkpoint's with fromTick, else 0). */
  startTick: number;
}

/** The record index and tick of the last checkpoint at or before `fromTick` (null when there is none). */
export async function findCheckpoint(file: string, fromTick: number): Promise<{ index: number; tick: number } | null> {
  const reader = await LogReader.open(file);
  let best: { index: number; tick: number } | null = null;
  try {
    for await (const e of reader.entries()) {
      if (e.type === 'checkpoint' && e.tick <= fromTick) best = { index: e.index, tick: e.tick };
      if (e.type === 'tick' && e.record.tick >= fromTick) break; // later checkpoints are past fromTick
    }
  } catch (err) {
    if (!(err instanceof LogCorruptError)) throw err; // the replay itself reports the damage
  } finally {
    await reader.close();
  }
  return best;
}

/**
 * The scenario a log replays with: the given module's (its name must be the log's, and its module hash too unless
 * `force`), else the built-in the log names. A mismatch is a ScenarioVersionError saying what differs.
 */
export async function scenarioForLog(file: string, header: LogHeader, opts: Pick<ReplayOptions, 'scenario' | 'force'>): Promise<{ def: ScenarioDefinition; note: string | null }> {
  let def = opts.scenario;
  if (def === undefined) {
    if (!scenarioNames().includes(header.scenario)) {
      throw new ScenarioVersionError(`${file} was recorded with scenario "${header.scenario}", which is not built in: pass its module with --scenario ./path/to/game.ts`);
    }
    def = scenarioNamed(header.scenario);
  } else if (def.name !== header.scenario) {
    throw new ScenarioVersionError(`${file} was recorded with scenario "${header.scenario}", but the module given with --scenario defines "${def.name}"`);
  }
  const hash = await scenarioModuleHash(def);
  if (hash === header.scenarioHash || header.scenarioHash === '') return { def, note: null };
  const what = `${file} was recorded with another version of scenario "${header.scenario}" (module hash ${shortHash(header.scenarioHash)} in the log, ${shortHash(hash)} now)`;
  if (!opts.force) throw new ScenarioVersionError(`${what}: its hashes will likely differ; pass --force to replay it anyway`);
  return { def, note: `${what}: replaying anyway (--force), hashes may differ` };
}

/** Replays one log file. Throws for an unreadable file or header (missing, not a log, unknown scenario). */
export async function replayLog(file: string, opts: ReplayOptions = {}): Promise<ReplayReport> {
  const fileBytes = (await stat(file)).size;
  if (opts.fromTick !== undefined && opts.collectHashes) throw new Error('replayLog: fromTick and collectHashes do not go together');
  const start = opts.fromTick !== undefined ? await findCheckpoint(file, opts.fromTick) : null;
  const reader = await LogReader.open(file);
  let sim: Simulation | null = null;
  try {
    const header = reader.header;
    const { def, note } = await scenarioForLog(file, header, opts);
    try {
      sim = await createSimulation(def, header.params, header.seed);
    } catch (err) {
      // The log, not the command line, names the scenario and parameters: a failure here is the log's problem.
      throw new Error(`${file} cannot be replayed by this build: ${(err as Error).message}`, { cause: err });
    }
    const s: Simulation = sim;
    const report: ReplayReport = { file, header, status: 'ok', log: 'complete', ticks: 0, hashesChecked: 0, finalHash: '', msPerTick: 0, droppedBytes: 0, startTick: 0 };
    let skipBefore = start?.index ?? 0;
    let skippedHash: { tick: number; hash: string; index: number; offset: number } | null = null;
    const jolt = installedJoltVersion();
    if (header.joltVersion !== jolt) report.joltVersionNote = `recorded with jolt-physics ${header.joltVersion}, replaying with ${jolt}: hashes may differ`;
    if (note) report.scenarioNote = note;
    const hashes = opts.collectHashes ? [s.stateHash()] : null;
    const toTick = opts.toTick ?? Number.POSITIVE_INFINITY;
    let stepMs = 0;
    let lastProgress = 0;
    const entries = reader.entries();
    try {
      for await (const e of entries) {
        if (e.index < skipBefore) {
          if (e.type === 'hash') skippedHash = { tick: e.tick, hash: e.hash, index: e.index, offset: e.offset };
          continue;
        }
        if (e.type === 'checkpoint' && e.index === skipBefore && start !== null) {
          skipBefore = 0;
          try {
            s.restoreCheckpointBytes(e.bytes);
          } catch (err) {
            throw new LogCorruptError(e.index, e.offset, `the checkpoint at tick ${e.tick} cannot be restored: ${err instanceof Error ? err.message : 'it threw'}`);
          }
          report.startTick = e.tick;
          // The hash recorded at the checkpoint's tick (written just before it) checks the restored state.
          if (skippedHash !== null && skippedHash.tick === e.tick) {
            report.hashesChecked++;
            const actual = s.stateHash();
            if (actual !== skippedHash.hash) {
              report.status = 'diverged';
              report.divergence = { tick: e.tick, expected: skippedHash.hash, actual, recordIndex: skippedHash.index, byteOffset: skippedHash.offset, state: null, stateNote: 'the recorded checkpoint does not restore to the state hash recorded with it' };
              break;
            }
          }
          continue;
        }
        if (e.type === 'tick') {
          if (s.tick >= toTick) break;
          const t0 = performance.now();
          try {
            s.step(e.record);
          } catch (err) {
            // A well-framed record the simulation cannot apply (a player joining twice, a world that cannot hold
            // what the record asks for): the log, not the replay, is at fault; the record names where.
            throw new LogCorruptError(e.index, e.offset, `the simulation cannot apply tick record ${e.record.tick}: ${err instanceof Error ? err.message : 'it threw'}`);
          }
          stepMs += performance.now() - t0;
          report.ticks++;
          if (hashes) hashes.push(s.stateHash());
          if (opts.onProgress && e.offset - lastProgress > fileBytes / 200) {
            lastProgress = e.offset;
            opts.onProgress(e.offset / fileBytes, s.tick);
          }
        } else if (e.type === 'hash' || e.type === 'end') {
          const actual = s.stateHash();
          report.hashesChecked++;
          if (actual !== e.hash) {
            report.status = 'diverged';
            report.divergence = await locateDivergence(s, def, entries, e, actual);
            break;
          }
        }
      }
    } catch (err) {
      if (!(err instanceof LogCorruptError)) throw err;
      report.status = 'corrupt';
      report.corruption = { recordIndex: err.recordIndex, byteOffset: err.byteOffset, reason: err.reason };
    }
    const outcome = reader.outcome;
    report.log = outcome?.status ?? (report.status === 'corrupt' ? 'corrupt' : 'stopped');
    if (outcome?.status === 'truncated') report.droppedBytes = outcome.fileBytes - outcome.validBytes;
    report.finalHash = s.stateHash();
    report.msPerTick = report.ticks > 0 ? stepMs / report.ticks : 0;
    if (hashes) report.hashes = hashes;
    return report;
  } finally {
    sim?.destroy();
    await reader.close();
  }
}

/**
 * After a hash mismatch at `bad.tick`, keeps replaying to the first recorded checkpoint at or after it, restores
 * that checkpoint into a second simulation and compares the two states: the recorded run's bodies against ours.
 */
async function locateDivergence(sim: Simulation, def: ScenarioDefinition, entries: AsyncGenerator<LogEntry>, bad: LogEntry & { hash: string; tick: number }, actual: string): Promise<ReplayDivergence> {
  const d: ReplayDivergence = { tick: bad.tick, expected: bad.hash, actual, recordIndex: bad.index, byteOffset: bad.offset, state: null };
  try {
    for await (const e of entries) {
      if (e.type === 'tick') sim.step(e.record);
      else if (e.type === 'checkpoint') {
        const recorded = await createSimulation(def, sim.params, sim.seed);
        try {
          recorded.restoreCheckpointBytes(e.bytes);
          const diff = sim.firstDivergence(recorded);
          if (diff) {
            d.state = { ...diff, checkpointTick: e.tick };
            const desc = diff.bodyId !== undefined ? (sim.bodyDescriptor(diff.bodyId) ?? recorded.bodyDescriptor(diff.bodyId)) : undefined;
            if (desc) d.state.body = desc.playerId !== undefined ? `player ${desc.playerId}'s character` : `${desc.motion} ${desc.shape.kind}`;
          }
          else d.stateNote = `the replay matches the recorded checkpoint at tick ${e.tick} again (the difference is outside the checkpointed state)`;
        } finally {
          recorded.destroy();
        }
        return d;
      }
    }
    d.stateNote = `the log has no checkpoint at or after tick ${bad.tick}, so the differing body cannot be named (record with --checkpoint-every)`;
  } catch (err) {
    d.stateNote = `could not compare with a recorded checkpoint: ${(err as Error).message}`;
  }
  return d;
}
