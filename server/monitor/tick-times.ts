// A room's recent tick durations for the monitor: a ring of the last ticks' wall times (p50/p99) and a running count
// of ticks (the monitor turns it into ticks per second). Recording is O(1) and allocates nothing.

/** How many recent ticks the percentiles cover (4 s at 60 Hz). */
export const TICK_TIMES_WINDOW = 240;

/** Durations of a room's recent ticks. */
export class TickTimes {
  private readonly ring = new Float64Array(TICK_TIMES_WINDOW);
  private filled = 0;
  private next = 0;
  /** Ticks recorded since the room opened. */
  count = 0;

  /** Records one tick's wall time (ms). */
  record(durationMs: number): void {
    this.ring[this.next] = durationMs;
    this.next = (this.next + 1) % TICK_TIMES_WINDOW;
    if (this.filled < TICK_TIMES_WINDOW) this.filled++;
    this.count++;
  }

  /** The p50 and p99 of the recent ticks (ms, nearest rank), or null before the first tick. */
  percentiles(): { p50Ms: number; p99Ms: number } | null {
    if (this.filled === 0) return null;
    const sorted = this.ring.slice(0, this.filled).sort();
    const rank = (q: number): number => sorted[Math.min(this.filled - 1, Math.ceil(q * this.filled) - 1)];
    return { p50Ms: rank(0.5), p99Ms: rank(0.99) };
  }
}
