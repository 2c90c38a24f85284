// Plays an input log (.taoslog) in the browser with this project's own Simulation: checks every recorded hash once
// through (naming the first tick where this browser disagrees), keeps fast checkpoints along the way, and then
// seeks to any tick by restoring the nearest checkpoint and stepping forward. Draws nothing itself.
import { readLogBytes } from '../../server/log/log-bytes.ts';
import type { LogHeader, LogStatus } from '../../server/log/log-format.ts';
import { getScenario } from '../../scenarios/index.ts';
import type { Checkpoint } from '../../shared/sim/checkpoint.ts';
import type { ScenarioDefinition } from '../../shared/sim/scenario.ts';
import { Simulation } from '../../shared/sim/simulation.ts';
import type { SnapshotView } from '../../shared/protocol/snapshot-frame.ts';
import type { BodyDescriptor, SimEvent, TickInputRecord } from '../../shared/sim/types.ts';
import { viewFromBodyStates } from '../app/body-view.ts';

/** Most fast checkpoints kept for seeking (they live on the 128 MB WASM heap). */
const MAX_CHECKPOINTS = 48;
/** Fewest ticks between two kept checkpoints. */
const MIN_CHECKPOINT_SPACING_TICKS = 30;
/** Work done between two yields to the page while verifying (ms). */
const VERIFY_SLICE_MS = 12;

/** What the one pass over the whole log found. */
export interface ReplayVerification {
  /** Recorded hashes compared with this browser's (end record included). */
  hashesChecked: number;
  /** The first tick counter whose recorded hash differs from this browser's, or null when all matched. */
  firstMismatchTick: number | null;
  expected: string | null;
  actual: string | null;
  /** Set when a tick record could not be applied: playback stops before it. */
  failure: string | null;
}

/** A log held in memory and a simulation that plays it. Call destroy() when done (it frees the WASM world). */
export class ReplayPlayer {
  readonly header: LogHeader;
  /** The scenario's world bounds (for framing a camera). */
  readonly bounds: ScenarioDefinition['bounds'];
  /** How the log itself ended (complete, unterminated, truncated, corrupt). */
  readonly logStatus: LogStatus;
  private readonly records: TickInputRecord[];
  /** Tick counter → recorded hashes (hash and end records; both may name the last tick). */
  private readonly recorded = new Map<number, string[]>();
  private readonly sim: Simulation;
  private readonly checkpoints = new Map<number, Checkpoint>();
  private readonly spacingTicks: number;
  private verified: ReplayVerification | null = null;
  /** Ticks this browser can play (fewer than the log's when a record cannot be applied). */
  private playable: number;
  private destroyed = false;

  private constructor(header: LogHeader, bounds: ScenarioDefinition['bounds'], logStatus: LogStatus, records: TickInputRecord[], sim: Simulation) {
    this.header = header;
    this.bounds = bounds;
    this.logStatus = logStatus;
    this.records = records;
    this.sim = sim;
    this.playable = records.length;
    this.spacingTicks = Math.max(MIN_CHECKPOINT_SPACING_TICKS, Math.ceil(records.length / MAX_CHECKPOINTS));
  }

  /** Reads a log's bytes and builds its scenario at tick 0. Throws a clear Error for a file that is not a usable log. */
  static async open(bytes: Uint8Array, source: string): Promise<ReplayPlayer> {
    const contents = readLogBytes(bytes, source);
    const { header } = contents;
    let sim: Simulation;
    let def: ScenarioDefinition;
    try {
      def = getScenario(header.scenario);
      sim = await Simulation.create({ scenario: def, params: header.params, seed: header.seed });
    } catch (err) {
      throw new Error(`${source} cannot be played by this build: ${(err as Error).message}`, { cause: err });
    }
    const records: TickInputRecord[] = [];
    const player = new ReplayPlayer(header, def.bounds, contents.outcome.status, records, sim);
    for (const e of contents.entries) {
      if (e.type === 'tick') records.push(e.record);
      else if (e.type === 'hash' || e.type === 'end') player.recorded.set(e.tick, [...(player.recorded.get(e.tick) ?? []), e.hash]);
    }
    player.playable = records.length;
    player.checkpoints.set(0, sim.saveCheckpoint());
    return player;
  }

  /** Tick records in the log. */
  get totalTicks(): number {
    return this.records.length;
  }

  /** The last tick counter playback can reach. */
  get lastTick(): number {
    return this.playable;
  }

  /** The simulation's tick counter (ticks applied). */
  get tick(): number {
    return this.sim.tick;
  }

  /** The verification result, once verify() has finished. */
  get verification(): ReplayVerification | null {
    return this.verified;
  }

  /** The state hash at the current tick. */
  stateHash(): string {
    return this.sim.stateHash();
  }

  /**
   * Plays the whole log once, comparing every recorded hash and keeping checkpoints for seeking; yields to the page
   * between slices and reports progress. Leaves the simulation at the last playable tick. Rejects if the player is
   * destroyed meanwhile (another log was opened).
   */
  async verify(onProgress?: (tick: number) => void): Promise<ReplayVerification> {
    if (this.verified) return this.verified;
    this.seek(0);
    const v: ReplayVerification = { hashesChecked: 0, firstMismatchTick: null, expected: null, actual: null, failure: null };
    const check = (): void => {
      const actual = this.sim.stateHash();
      for (const expected of this.recorded.get(this.sim.tick) ?? []) {
        v.hashesChecked++;
        if (actual !== expected && v.firstMismatchTick === null) {
          v.firstMismatchTick = this.sim.tick;
          v.expected = expected;
          v.actual = actual;
        }
      }
    };
    check();
    onProgress?.(0);
    let sliceStart = performance.now();
    while (this.sim.tick < this.records.length) {
      if (this.destroyed) throw new Error('the replay was closed while its hashes were being checked');
      try {
        this.sim.step(this.records[this.sim.tick]);
      } catch (err) {
        v.failure = `tick record ${this.sim.tick} cannot be applied: ${(err as Error).message}`;
        this.playable = this.sim.tick;
        break;
      }
      check();
      if (this.sim.tick % this.spacingTicks === 0 && !this.checkpoints.has(this.sim.tick)) this.checkpoints.set(this.sim.tick, this.sim.saveCheckpoint());
      if (performance.now() - sliceStart > VERIFY_SLICE_MS) {
        onProgress?.(this.sim.tick);
        await new Promise<void>((resolve) => setTimeout(resolve, 0));
        sliceStart = performance.now();
      }
    }
    onProgress?.(this.sim.tick);
    this.verified = v;
    return v;
  }

  /**
   * Moves to tick counter `tick` (clamped to what can be played). Returns the events of the ticks stepped when it
   * only stepped forward a little (`jumped: false`), or `jumped: true` when it restored a checkpoint: the caller
   * then redraws the world from descriptors() instead of applying events.
   */
  seek(tick: number): { jumped: boolean; events: SimEvent[] } {
    const target = Math.max(0, Math.min(this.playable, Math.floor(tick)));
    const events: SimEvent[] = [];
    if (target === this.sim.tick) return { jumped: false, events };
    let jumped = false;
    if (target < this.sim.tick || target - this.sim.tick > this.spacingTicks) {
      const from = this.nearestCheckpoint(target);
      if (from.tick > this.sim.tick || target < this.sim.tick) {
        this.sim.restoreCheckpoint(from);
        jumped = true;
      }
    }
    while (this.sim.tick < target) {
      const stepped = this.sim.step(this.records[this.sim.tick]);
      if (!jumped) events.push(...stepped);
    }
    return { jumped, events };
  }

  /** Descriptors of every live body at the current tick (ascending id). */
  descriptors(): BodyDescriptor[] {
    return this.sim.descriptors();
  }

  /** A body's descriptor at the current tick. */
  bodyDescriptor(id: number): BodyDescriptor | undefined {
    return this.sim.bodyDescriptor(id);
  }

  /** Every player who joins somewhere in the log (ascending id), with the name they joined under. */
  playersInLog(): Array<{ playerId: number; name: string }> {
    const seen = new Map<number, string>();
    for (const r of this.records) for (const j of r.joins) if (!seen.has(j.playerId)) seen.set(j.playerId, j.name);
    return [...seen.entries()].sort((a, b) => a[0] - b[0]).map(([playerId, name]) => ({ playerId, name }));
  }

  /** Players present at the current tick (ascending id). */
  playerIds(): number[] {
    return this.sim.playerIds();
  }

  /** The moving bodies and characters of the current tick, copied out. */
  frame(): SnapshotView {
    return viewFromBodyStates(this.sim.tick, this.sim.readBodyStates(), this.sim.characters());
  }

  /** Frees the checkpoints and the simulation. */
  destroy(): void {
    if (this.destroyed) return;
    this.destroyed = true;
    for (const cp of this.checkpoints.values()) cp.dispose();
    this.checkpoints.clear();
    this.sim.destroy();
  }

  private nearestCheckpoint(tick: number): Checkpoint {
    let best = this.checkpoints.get(0)!;
    for (const [t, cp] of this.checkpoints) if (t <= tick && t > best.tick) best = cp;
    return best;
  }
}
