// Rolling frame statistics for the HUD and the test hook: frames per second, frame interval and CPU time per frame.
// Pure bookkeeping over timestamps the caller passes in (milliseconds), so it is unit-testable.

/** Summary of the last window of frames. */
export interface FrameTimingSummary {
  frames: number;
  fps: number;
  meanIntervalMs: number;
  p50IntervalMs: number;
  p95IntervalMs: number;
  meanCpuMs: number;
  p95CpuMs: number;
}

/** Keeps the last `capacity` frame intervals and CPU times. */
export class FrameTimer {
  private readonly intervals: Float64Array;
  private readonly cpu: Float64Array;
  private count = 0;
  private next = 0;
  private lastStartMs: number | null = null;
  /** Frames recorded since creation. */
  total = 0;

  constructor(capacity = 240) {
    if (!Number.isInteger(capacity) || capacity < 2) throw new Error(`FrameTimer: capacity must be an integer >= 2, got ${capacity}`);
    this.intervals = new Float64Array(capacity);
    this.cpu = new Float64Array(capacity);
  }

  /** Records one frame that started at `startMs` and spent `cpuMs` in our code. */
  record(startMs: number, cpuMs: number): void {
    if (this.lastStartMs !== null) {
      this.intervals[this.next] = Math.max(0, startMs - this.lastStartMs);
      this.cpu[this.next] = Math.max(0, cpuMs);
      this.next = (this.next + 1) % this.intervals.length;
      this.count = Math.min(this.count + 1, this.intervals.length);
    }
    this.lastStartMs = startMs;
    this.total++;
  }

  /** Statistics over the recorded window (zeros before two frames). */
  summary(): FrameTimingSummary {
    if (this.count === 0) return { frames: this.total, fps: 0, meanIntervalMs: 0, p50IntervalMs: 0, p95IntervalMs: 0, meanCpuMs: 0, p95CpuMs: 0 };
    const iv = Array.from(this.intervals.subarray(0, this.count)).sort((a, b) => a - b);
    const cpu = Array.from(this.cpu.subarray(0, this.count)).sort((a, b) => a - b);
    const mean = (a: number[]): number => a.reduce((s, v) => s + v, 0) / a.length;
    const pct = (a: number[], p: number): number => a[Math.min(a.length - 1, Math.floor(p * a.length))];
    const meanInterval = mean(iv);
    return {
      frames: this.total,
      fps: meanInterval > 0 ? 1000 / meanInterval : 0,
      meanIntervalMs: meanInterval,
      p50IntervalMs: pct(iv, 0.5),
      p95IntervalMs: pct(iv, 0.95),
      meanCpuMs: mean(cpu),
      p95CpuMs: pct(cpu, 0.95),
    };
  }
}
