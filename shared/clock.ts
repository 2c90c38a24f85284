// Time as the server and the client library see it: the Clock contract (monotonic milliseconds + one-shot timers),
// the manual clock tests advance by hand, and TimerClock, which runs the contract on timer functions the platform
// hands in (sdk/clock.ts and server/clock.ts bind performance.now + setTimeout). Pure: it never reads time itself.

/** Opaque handle of a scheduled timer. */
export type TimerHandle = { readonly id: number };

/** A monotonic millisecond clock with one-shot timers. */
export interface Clock {
  /** Monotonic time in milliseconds (arbitrary origin; never goes back). */
  nowMs(): number;
  /** Runs `fn` once after `delayMs` (≥ 0). */
  setTimer(delayMs: number, fn: () => void): TimerHandle;
  /** Cancels a timer (no-op when it already ran or was cleared). */
  clearTimer(handle: TimerHandle): void;
}

/** The platform's time functions a TimerClock runs on; `T` is the platform's own timer token. */
export interface TimerSource<T> {
  /** Monotonic milliseconds. */
  now(): number;
  /** Schedules `fn` after `delayMs` (≥ 0) and returns the platform's token for it. */
  start(delayMs: number, fn: () => void): T;
  /** Cancels a token start() returned (the timer has not run yet). */
  cancel(token: T): void;
}

/** A Clock on real platform timers: hands out small numeric handles and forgets a timer once it ran or was cleared. */
export class TimerClock<T> implements Clock {
  private readonly source: TimerSource<T>;
  private nextId = 1;
  private readonly timers = new Map<number, T>();

  constructor(source: TimerSource<T>) {
    this.source = source;
  }

  nowMs(): number {
    return this.source.now();
  }

  setTimer(delayMs: number, fn: () => void): TimerHandle {
    const id = this.nextId++;
    const t = this.source.start(Math.max(0, delayMs), () => {
      this.timers.delete(id);
      fn();
    });
    this.timers.set(id, t);
    return { id };
  }

  clearTimer(handle: TimerHandle): void {
    const t = this.timers.get(handle.id);
    if (t !== undefined) {
      this.source.cancel(t);
      this.timers.delete(handle.id);
    }
  }
}

interface ManualTimer {
  id: number;
  dueMs: number;
  fn: () => void;
}

/**
 * A clock that only moves when told to. `advance(ms)` fires due timers in time order (ties in scheduling order),
 * with `nowMs()` reading each timer's due time while it runs, so code under test sees a consistent timeline.
 */
export class ManualClock implements Clock {
  private now: number;
  private nextId = 1;
  private timers: ManualTimer[] = [];

  constructor(startMs = 0) {
    this.now = startMs;
  }

  nowMs(): number {
    return this.now;
  }

  setTimer(delayMs: number, fn: () => void): TimerHandle {
    if (!Number.isFinite(delayMs)) throw new Error(`ManualClock.setTimer: delayMs must be finite, got ${delayMs}`);
    const id = this.nextId++;
    this.timers.push({ id, dueMs: this.now + Math.max(0, delayMs), fn });
    return { id };
  }

  clearTimer(handle: TimerHandle): void {
    this.timers = this.timers.filter((t) => t.id !== handle.id);
  }

  /** Number of timers still pending. */
  pendingTimers(): number {
    return this.timers.length;
  }

  /** Moves time forward by `ms`, running every timer that falls due on the way (including ones they schedule). */
  advance(ms: number): void {
    if (!Number.isFinite(ms) || ms < 0) throw new Error(`ManualClock.advance: ms must be a finite number ≥ 0, got ${ms}`);
    const end = this.now + ms;
    for (;;) {
      let next: ManualTimer | null = null;
      for (const t of this.timers) {
        if (t.dueMs <= end && (next === null || t.dueMs < next.dueMs || (t.dueMs === next.dueMs && t.id < next.id))) next = t;
      }
      if (next === null) break;
      const fired = next;
      this.timers = this.timers.filter((t) => t !== fired);
      if (fired.dueMs > this.now) this.now = fired.dueMs;
      fired.fn();
    }
    // A timer may itself have advanced the clock (a slow tick in a test): time never goes back.
    if (end > this.now) this.now = end;
  }
}
