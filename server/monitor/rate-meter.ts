// A per-second rate from a cumulative counter sampled now and then (bytes → kbps, ticks → ticks/s): the slope over the
// samples of the last few seconds, so one late sample does not make the figure jump.

/** Samples older than this are dropped (ms). */
const WINDOW_MS = 5000;

/** The rate of one cumulative counter. */
export class RateMeter {
  private readonly times: number[] = [];
  private readonly values: number[] = [];

  /** Adds a sample of the counter at `nowMs`. */
  sample(nowMs: number, cumulative: number): void {
    this.times.push(nowMs);
    this.values.push(cumulative);
    while (this.times.length > 2 && nowMs - this.times[0] > WINDOW_MS) {
      this.times.shift();
      this.values.shift();
    }
  }

  /** Units per second over the window; 0 until two samples at different times exist. */
  perSecond(): number {
    const n = this.times.length;
    if (n < 2) return 0;
    const dtMs = this.times[n - 1] - this.times[0];
    return dtMs > 0 ? ((this.values[n - 1] - this.values[0]) * 1000) / dtMs : 0;
  }
}
