// The fixed-rate tick driver: tick k is due at origin + k × dt on a monotonic Clock (absolute targets, so no drift),
// the origin placed on the room's phase of its thread's tick period when it has one (tick-phases.ts). A few late ticks
// are caught up (past the first of a wake-up, only while its thread's catch-up budget allows); a room further behind
// than the catch-up limit runs one tick, gives up the rest of the lost time and says so, instead of running a burst.
import type { Clock, TimerHandle } from '../shared/clock.ts';
import type { CatchUpGate } from './catch-up-budget.ts';
import { nextPhaseTimeMs } from './tick-phases.ts';
import { TICK_RATE_HZ } from '../shared/tick-rate.ts';

/** What the driver reports when it had to give up time instead of catching up. */
export interface SlowdownReport {
  /** The next tick to run when the slowdown happened. */
  tick: number;
  /** Ticks that were due but not run (the simulation falls behind wall time by this many ticks). */
  skippedTicks: number;
  /** Milliseconds given up. */
  lostMs: number;
}

/** Options of TickClock. */
export interface TickClockOptions {
  clock: Clock;
  /** Ticks per second; default TICK_RATE_HZ (60). */
  tickRateHz?: number;
  /** Most overdue ticks that are caught up; a room further behind runs one tick and gives up the rest. Default 4. */
  maxCatchUpTicks?: number;
  /**
   * Where in the tick period this clock ticks (ms in [0, dt), counted from the clock's zero): start() and a slowdown
   * put the next tick on it. Default none: start() ticks at once and a slowdown ticks one dt later.
   */
  phaseMs?: number | null;
  /** Runs one tick (its index counts from 0 at start()). An exception stops the clock and goes to onError. */
  onTick: (tick: number) => void;
  /** Called after a slowdown. */
  onSlowdown?: (report: SlowdownReport) => void;
  /** Called when onTick throws; the clock is stopped first. */
  onError?: (error: unknown) => void;
  /** The thread's catch-up budget: overdue ticks past the first of a wake-up run only while it allows. Default none. */
  catchUp?: CatchUpGate | null;
}

// Float slack when comparing a due time to "now" (a manual clock lands exactly on due times modulo rounding).
const EPSILON_MS = 1e-6;

/** Drives onTick at a fixed rate; start() with a timer-driven loop, or call poll() yourself. */
export class TickClock {
  readonly tickRateHz: number;
  readonly dtMs: number;
  readonly maxCatchUpTicks: number;
  private readonly clock: Clock;
  private readonly onTick: (tick: number) => void;
  private readonly onSlowdown: ((r: SlowdownReport) => void) | undefined;
  private readonly onError: ((e: unknown) => void) | undefined;
  private readonly catchUp: CatchUpGate | null;
  private readonly phaseMs: number | null;
  private originMs = 0;
  private ticks = 0;
  private running = false;
  private timer: TimerHandle | null = null;
  private slowdownCount = 0;
  private skippedTotal = 0;

  constructor(opts: TickClockOptions) {
    const rate = opts.tickRateHz ?? TICK_RATE_HZ;
    if (!Number.isFinite(rate) || rate <= 0 || rate > 1000) throw new Error(`TickClock: tickRateHz must be in (0, 1000], got ${rate}`);
    const catchUp = opts.maxCatchUpTicks ?? 4;
    if (!Number.isInteger(catchUp) || catchUp < 1 || catchUp > 100) throw new Error(`TickClock: maxCatchUpTicks must be an integer in [1, 100], got ${catchUp}`);
    this.tickRateHz = rate;
    this.dtMs = 1000 / rate;
    this.maxCatchUpTicks = catchUp;
    this.clock = opts.clock;
    this.onTick = opts.onTick;
    this.onSlowdown = opts.onSlowdown;
    this.onError = opts.onError;
    this.catchUp = opts.catchUp ?? null;
    const phase = opts.phaseMs ?? null;
    if (phase !== null && !(phase >= 0 && phase < this.dtMs)) throw new Error(`TickClock: phaseMs must be in [0, ${this.dtMs}), got ${phase}`);
    this.phaseMs = phase;
  }

  /** Ticks run so far (the index the next tick will get). */
  get ticksRun(): number {
    return this.ticks;
  }

  /** How many slowdowns happened. */
  get slowdowns(): number {
    return this.slowdownCount;
  }

  /** Ticks given up in all slowdowns. */
  get skippedTicks(): number {
    return this.skippedTotal;
  }

  /** Whether the timer loop is running. */
  get isRunning(): boolean {
    return this.running;
  }

  /** Monotonic time at which the next tick is due. */
  nextDueMs(): number {
    return this.dueAt(this.ticks);
  }

  /** Milliseconds the next tick is overdue (0 when on time). */
  lagMs(): number {
    return Math.max(0, this.clock.nowMs() - this.dueAt(this.ticks));
  }

  /** Starts the timer loop; the next tick is due now, or at the clock's phase when it has one. */
  start(): void {
    if (this.running) return;
    this.running = true;
    const now = this.clock.nowMs();
    const firstMs = this.phaseMs === null ? now : nextPhaseTimeMs(now, this.dtMs, this.phaseMs);
    this.originMs = firstMs - this.ticks * this.dtMs;
    this.schedule();
  }

  /** Stops the timer loop (the tick count is kept; start() resumes without catching up on the pause). */
  stop(): void {
    this.running = false;
    if (this.timer) this.clock.clearTimer(this.timer);
    this.timer = null;
  }

  /**
   * Runs the ticks due now. Up to maxCatchUpTicks overdue run (past the first, only while the catch-up budget allows:
   * the rest stay due for the next wake-up). More overdue than that: the room is too far behind for catching up to
   * help, so it runs one tick, gives up the rest (the next tick is due one dt from now, or at its phase at least half a
   * dt from now) and reports a slowdown: a burst of back-to-back ticks would only stall its thread's other rooms.
   * Returns how many ticks ran.
   */
  poll(): number {
    const now = this.clock.nowMs();
    let due = 0;
    while (due <= this.maxCatchUpTicks && this.dueAt(this.ticks + due) <= now + EPSILON_MS) due++;
    if (due > this.maxCatchUpTicks) {
      // Count every overdue tick but the one run now, then re-anchor.
      const skipped = Math.floor((now - this.dueAt(this.ticks)) / this.dtMs + EPSILON_MS);
      this.runTick();
      const nextMs = this.phaseMs === null ? now + this.dtMs : nextPhaseTimeMs(now + this.dtMs / 2, this.dtMs, this.phaseMs);
      this.originMs = nextMs - this.ticks * this.dtMs;
      this.slowdownCount++;
      this.skippedTotal += skipped;
      this.onSlowdown?.({ tick: this.ticks, skippedTicks: skipped, lostMs: skipped * this.dtMs });
      return 1;
    }
    let run = 0;
    for (; run < due; run++) {
      if (run > 0 && this.catchUp !== null && !this.catchUp.allows()) break;
      this.runTick();
    }
    return run;
  }

  private runTick(): void {
    const tick = this.ticks;
    this.ticks++;
    const startedMs = this.catchUp === null ? 0 : performance.now();
    this.onTick(tick);
    this.catchUp?.spend(performance.now() - startedMs);
  }

  private dueAt(tick: number): number {
    return this.originMs + (tick * 1000) / this.tickRateHz;
  }

  private schedule(): void {
    if (!this.running) return;
    const delay = Math.max(0, this.dueAt(this.ticks) - this.clock.nowMs());
    this.timer = this.clock.setTimer(delay, () => {
      this.timer = null;
      if (!this.running) return;
      try {
        this.poll();
      } catch (error) {
        this.stop();
        if (this.onError) this.onError(error);
        else throw error;
        return;
      }
      this.schedule();
    });
  }
}
