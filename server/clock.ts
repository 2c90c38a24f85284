// Time sources for the server: a monotonic clock with timers (system) and a manual one tests advance by hand.
// Everything time-driven in server/ (tick loop, grace periods, rate limits, pings) reads time only through a Clock.

import type { Clock, TimerHandle } from '../sdk/clock.ts';

// One Clock contract and one real clock (performance.now() + setTimeout) for both ends: the client library defines
// them (browser + Node); the server adds the manual clock its tests drive.
export type { Clock, TimerHandle };
export { RealClock as SystemClock } from '../sdk/clock.ts';

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
