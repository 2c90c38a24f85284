// What the HUD and net graph show about the connection: snapshot rate, bytes in, arrival jitter and interpolation
// buffer depth over the last seconds. Pure bookkeeping over timestamps the caller passes in (ms), unit-testable.
import { TICK_RATE_HZ } from '../../shared/tick-rate.ts';

/** One sample of a series: time (ms) and value. */
export interface SeriesPoint {
  timeMs: number;
  value: number;
}

/** Keeps timestamped samples for a sliding window. */
class Series {
  readonly points: SeriesPoint[] = [];
  push(timeMs: number, value: number): void {
    this.points.push({ timeMs, value });
  }
  trim(oldestMs: number): void {
    let drop = 0;
    while (drop < this.points.length && this.points[drop].timeMs < oldestMs) drop++;
    if (drop > 0) this.points.splice(0, drop);
  }
}

/** Connection statistics over a sliding window (default 5 s). */
export class NetHistory {
  readonly windowMs: number;
  readonly tickMs: number;
  private readonly snapshots = new Series();
  private readonly bytes = new Series();
  private readonly jitter = new Series();
  private readonly depth = new Series();
  private lastArrivalMs: number | null = null;
  private lastTick: number | null = null;

  constructor(tickRateHz = TICK_RATE_HZ, windowMs = 5000) {
    if (!(tickRateHz > 0) || !(windowMs > 0)) throw new Error(`NetHistory: tick rate and window must be > 0, got ${tickRateHz}, ${windowMs}`);
    this.tickMs = 1000 / tickRateHz;
    this.windowMs = windowMs;
  }

  /**
   * Records a snapshot for `tick` arriving at `nowMs`. Jitter is how far its arrival interval strays from the
   * interval its tick number implies (late and early both count); duplicates and reordered ones add no jitter.
   */
  recordSnapshot(nowMs: number, tick: number): void {
    this.snapshots.push(nowMs, tick);
    if (this.lastArrivalMs !== null && this.lastTick !== null && tick > this.lastTick) {
      const expected = (tick - this.lastTick) * this.tickMs;
      this.jitter.push(nowMs, Math.abs(nowMs - this.lastArrivalMs - expected));
    }
    if (this.lastTick === null || tick > this.lastTick) {
      this.lastTick = tick;
      this.lastArrivalMs = nowMs;
    }
    this.trim(nowMs);
  }

  /** Records bytes received (any message). */
  recordBytes(nowMs: number, sizeBytes: number): void {
    this.bytes.push(nowMs, sizeBytes);
    this.trim(nowMs);
  }

  /** Records how many snapshots sit ahead of the render time (sampled per frame). */
  recordBufferDepth(nowMs: number, snapshotsAhead: number): void {
    this.depth.push(nowMs, snapshotsAhead);
    this.trim(nowMs);
  }

  /** Snapshots received per second over the last second. */
  snapshotsPerSecond(nowMs: number): number {
    return this.snapshots.points.filter((p) => p.timeMs > nowMs - 1000).length;
  }

  /** Kilobits per second received over the last second. */
  kbpsIn(nowMs: number): number {
    let sum = 0;
    for (const p of this.bytes.points) if (p.timeMs > nowMs - 1000) sum += p.value;
    return (sum * 8) / 1000;
  }

  /** Mean arrival jitter (ms) over the window; 0 before two snapshots. */
  meanJitterMs(): number {
    const pts = this.jitter.points;
    return pts.length === 0 ? 0 : pts.reduce((s, p) => s + p.value, 0) / pts.length;
  }

  /** The window's jitter and buffer-depth samples (oldest first) for the graph. */
  series(): { jitter: readonly SeriesPoint[]; depth: readonly SeriesPoint[] } {
    return { jitter: this.jitter.points, depth: this.depth.points };
  }

  private trim(nowMs: number): void {
    const oldest = nowMs - this.windowMs;
    this.snapshots.trim(oldest);
    this.bytes.trim(oldest);
    this.jitter.trim(oldest);
    this.depth.trim(oldest);
  }
}
