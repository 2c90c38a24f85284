// Where in the tick period each room of one thread ticks: rooms that share an event loop get phases spread over the
// period (the widest free gap first), so their ticks interleave with each other and with socket work instead of
// queueing behind one another at the same instant, and a room that slowed down rejoins its own phase, not its
// neighbours'. Room workers sharing cores start their phases at different offsets (workerPhaseOffsetMs) so their
// rooms' ticks interleave across threads as well. Pure bookkeeping: the TickClock turns a phase into due times.
import { TICK_MS } from '../shared/tick-rate.ts';

/** The first time at or after `nowMs` that lies `phaseMs` past a whole multiple of `periodMs` (from the clock's zero). */
export function nextPhaseTimeMs(nowMs: number, periodMs: number, phaseMs: number): number {
  if (!(periodMs > 0) || !(phaseMs >= 0 && phaseMs < periodMs)) throw new Error(`nextPhaseTimeMs: needs periodMs > 0 and phaseMs in [0, periodMs), got ${periodMs}, ${phaseMs}`);
  const cycles = Math.ceil((nowMs - phaseMs) / periodMs - 1e-9);
  return cycles * periodMs + phaseMs;
}

/**
 * Where room worker `index` of `count` starts its phases: workers a sixteenth of the period apart divided by their
 * count, so up to 16 rooms per worker interleave with the other workers' instead of ticking at the same instants.
 */
export function workerPhaseOffsetMs(index: number, count: number, periodMs = TICK_MS): number {
  if (!(Number.isInteger(index) && Number.isInteger(count) && index >= 0 && index < count)) throw new Error(`workerPhaseOffsetMs: needs 0 ≤ index < count, got ${index}, ${count}`);
  return ((index / count) * periodMs) / 16;
}

/** A thread's tick phases: take() one per room when it opens, release() it when the room closes. */
export class TickPhases {
  readonly periodMs: number;
  /** The first room's phase (the rest spread around it). */
  readonly offsetMs: number;
  private readonly held: number[] = [];

  constructor(periodMs = TICK_MS, offsetMs = 0) {
    if (!(periodMs > 0)) throw new Error(`TickPhases: periodMs must be > 0, got ${periodMs}`);
    if (!(offsetMs >= 0 && offsetMs < periodMs)) throw new Error(`TickPhases: offsetMs must be in [0, periodMs), got ${offsetMs}`);
    this.periodMs = periodMs;
    this.offsetMs = offsetMs;
  }

  /** Phases in use, ascending. */
  get phases(): readonly number[] {
    return this.held;
  }

  /** The middle of the widest gap between the phases in use (offsetMs for the first; ties go to the earliest gap). */
  take(): number {
    let phase = this.offsetMs;
    if (this.held.length > 0) {
      let widest = -1;
      for (let i = 0; i < this.held.length; i++) {
        const from = this.held[i];
        const to = i + 1 < this.held.length ? this.held[i + 1] : this.held[0] + this.periodMs;
        if (to - from > widest + 1e-9) {
          widest = to - from;
          phase = (from + (to - from) / 2) % this.periodMs;
        }
      }
    }
    this.held.push(phase);
    this.held.sort((a, b) => a - b);
    return phase;
  }

  /** Gives a phase back (a closed room's); unknown phases are ignored. */
  release(phaseMs: number): void {
    const i = this.held.indexOf(phaseMs);
    if (i >= 0) this.held.splice(i, 1);
  }
}
