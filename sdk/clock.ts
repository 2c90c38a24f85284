// Time for the client library: a monotonic millisecond clock that can schedule callbacks. The browser/Node clock
// uses performance.now() and setTimeout; tests pass a manual clock with the same shape (e.g. server/clock.ts's).

/** Opaque handle of a scheduled timer. */
export type TimerHandle = { readonly id: number };

/** A monotonic millisecond clock with one-shot timers (structurally the same as the server's Clock). */
export interface Clock {
  /** Monotonic time in milliseconds (arbitrary origin; never goes back). */
  nowMs(): number;
  /** Runs `fn` once after `delayMs` (≥ 0). */
  setTimer(delayMs: number, fn: () => void): TimerHandle;
  /** Cancels a timer (no-op when it already ran or was cleared). */
  clearTimer(handle: TimerHandle): void;
}

/** The real clock of a browser page or Node 24: performance.now() and setTimeout. */
export class RealClock implements Clock {
  private nextId = 1;
  private readonly timers = new Map<number, ReturnType<typeof setTimeout>>();

  nowMs(): number {
    return performance.now();
  }

  setTimer(delayMs: number, fn: () => void): TimerHandle {
    const id = this.nextId++;
    const t = setTimeout(
      () => {
        this.timers.delete(id);
        fn();
      },
      Math.max(0, delayMs),
    );
    this.timers.set(id, t);
    return { id };
  }

  clearTimer(handle: TimerHandle): void {
    const t = this.timers.get(handle.id);
    if (t !== undefined) {
      clearTimeout(t);
      this.timers.delete(handle.id);
    }
  }
}
