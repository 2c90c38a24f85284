// One player's pending inputs keyed by the tick they are for: accepts validated commands within a bounded window
// ahead of the server tick, hands out exactly one command per tick (repeating the last one when none arrived).
import { NEUTRAL_INPUT, type InputCommand } from '../shared/sim/input.ts';

/** What happened to one offered input. */
export const OfferResult = {
  /** Stored for its tick. */
  Accepted: 'accepted',
  /** A command for that tick was already stored or applied (a redundant copy): ignored. */
  Duplicate: 'duplicate',
  /** Its tick was already applied with a repeated command (this one came too late): dropped. */
  Late: 'late',
  /** Its tick is further ahead than the window allows: dropped. */
  TooFar: 'tooFar',
} as const;
export type OfferResult = (typeof OfferResult)[keyof typeof OfferResult];

/** Running counts of one buffer. */
export interface InputBufferStats {
  accepted: number;
  duplicates: number;
  late: number;
  tooFar: number;
  /** Ticks applied with a repeated command because none had arrived. */
  repeated: number;
  /** Ticks applied with the hold command while the player's link was down (not counted as repeated). */
  held: number;
}

const HISTORY = 256;

/** Everything an InputBuffer holds, as plain data (a room moving to another thread takes its buffers along). */
export interface InputBufferState {
  maxLeadTicks: number;
  nextTick: number;
  last: InputCommand;
  suspended: boolean;
  /** [tick, command] pairs still waiting. */
  pending: Array<[number, InputCommand]>;
  appliedTick: number[];
  appliedOwn: number[];
  stats: InputBufferStats;
}

/** A per-player input buffer; `take(tick)` must be called with consecutive ticks. */
export class InputBuffer {
  /** Furthest ahead of the next tick to apply an input may be stamped. */
  readonly maxLeadTicks: number;
  private readonly pending = new Map<number, InputCommand>();
  private last: InputCommand = NEUTRAL_INPUT;
  private nextTick: number;
  private suspended = false;
  // The last HISTORY applied ticks: which tick sits in each slot, and whether its own command had arrived, so a
  // redundant copy of an applied input is told apart from an input that really came too late.
  private readonly appliedTick = new Float64Array(HISTORY).fill(-1);
  private readonly appliedOwn = new Uint8Array(HISTORY);
  readonly stats: InputBufferStats = { accepted: 0, duplicates: 0, late: 0, tooFar: 0, repeated: 0, held: 0 };

  /** `firstTick` is the first tick this player's commands will be applied on. */
  constructor(firstTick: number, maxLeadTicks = 120) {
    if (!Number.isInteger(firstTick) || firstTick < 0) throw new Error(`InputBuffer: firstTick must be an integer ≥ 0, got ${firstTick}`);
    if (!Number.isInteger(maxLeadTicks) || maxLeadTicks < 1) throw new Error(`InputBuffer: maxLeadTicks must be an integer ≥ 1, got ${maxLeadTicks}`);
    this.nextTick = firstTick;
    this.maxLeadTicks = maxLeadTicks;
  }

  /** A buffer continuing exactly where `state` (from exportState) left off. */
  static fromState(state: InputBufferState): InputBuffer {
    const b = new InputBuffer(state.nextTick, state.maxLeadTicks);
    b.last = state.last;
    b.suspended = state.suspended;
    for (const [tick, command] of state.pending) b.pending.set(tick, command);
    b.appliedTick.set(state.appliedTick);
    b.appliedOwn.set(state.appliedOwn);
    Object.assign(b.stats, state.stats);
    return b;
  }

  /** The buffer's whole state as plain data. */
  exportState(): InputBufferState {
    return {
      maxLeadTicks: this.maxLeadTicks,
      nextTick: this.nextTick,
      last: this.last,
      suspended: this.suspended,
      pending: [...this.pending],
      appliedTick: [...this.appliedTick],
      appliedOwn: [...this.appliedOwn],
      stats: { ...this.stats },
    };
  }

  /** The next tick take() will serve. */
  get nextTickToApply(): number {
    return this.nextTick;
  }

  /** How many commands are waiting. */
  get size(): number {
    return this.pending.size;
  }

  /** The command applied most recently (neutral before the first). */
  get lastApplied(): InputCommand {
    return this.last;
  }

  /** Whether the buffer is suspended (its player's link is down). */
  get isSuspended(): boolean {
    return this.suspended;
  }

  /**
   * The player's link dropped: commands still waiting are discarded, and until resume() every tick applies `hold`
   * (counted as held, not as repeated). After resume() `hold` stays the command repeated when none arrives.
   */
  suspend(hold: InputCommand): void {
    this.suspended = true;
    this.pending.clear();
    this.last = hold;
  }

  /** The player is back: offered commands apply again from the next tick. */
  resume(): void {
    this.suspended = false;
  }

  /** Offers an already-validated command for `tick`. The first copy for a tick wins; the buffer never grows past the window. */
  offer(tick: number, command: InputCommand): OfferResult {
    if (tick < this.nextTick) {
      const slot = tick % HISTORY;
      if (this.appliedTick[slot] === tick && this.appliedOwn[slot] === 1) {
        this.stats.duplicates++;
        return OfferResult.Duplicate;
      }
      this.stats.late++;
      return OfferResult.Late;
    }
    if (tick > this.nextTick + this.maxLeadTicks) {
      this.stats.tooFar++;
      return OfferResult.TooFar;
    }
    if (this.pending.has(tick)) {
      this.stats.duplicates++;
      return OfferResult.Duplicate;
    }
    this.pending.set(tick, command);
    this.stats.accepted++;
    return OfferResult.Accepted;
  }

  /** The command to apply on `tick` (which must be the next tick): the one stamped for it, else the last one again. */
  take(tick: number): { command: InputCommand; repeated: boolean } {
    if (tick !== this.nextTick) throw new Error(`InputBuffer.take: expected tick ${this.nextTick}, got ${tick}`);
    this.nextTick = tick + 1;
    if (this.suspended) {
      this.pending.delete(tick);
      this.appliedTick[tick % HISTORY] = tick;
      this.appliedOwn[tick % HISTORY] = 0;
      this.stats.held++;
      return { command: this.last, repeated: false };
    }
    const cmd = this.pending.get(tick);
    this.appliedTick[tick % HISTORY] = tick;
    this.appliedOwn[tick % HISTORY] = cmd !== undefined ? 1 : 0;
    if (cmd !== undefined) {
      this.pending.delete(tick);
      this.last = cmd;
      return { command: cmd, repeated: false };
    }
    this.stats.repeated++;
    return { command: this.last, repeated: true };
  }
}
