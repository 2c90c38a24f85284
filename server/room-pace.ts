// A room's pace as its players feel it: ticks run per second over the last second, the 99th percentile of its recent
// tick times, and whether it has given up ticks lately (it cannot keep the tick rate and runs slowed). Shown in the room list, /metrics and the room workers' status.
import type { Clock } from '../shared/clock.ts';

/** How long a room counts as slow after it last gave up ticks. */
export const SLOW_HOLD_MS = 2000;
const WINDOW_MS = 1000;
/** Tick times kept for the percentile: the last 10 s at 60 Hz. */
const TICK_TIMES_KEPT = 600;

/** What RoomInfo reports of a room's pace. */
export interface PaceReport {
  /** Ticks run per second over the last second (0 while the room is paused or stalled). */
  ticksPerSecond: number;
  /** True while the room cannot keep the tick rate (it gave up ticks within the last SLOW_HOLD_MS). */
  slow: boolean;
  /** 99th percentile of the wall time of its last 600 ticks, in ms (null before the first tick). */
  tickMsP99: number | null;
  /** 99th percentile of the CPU time its thread spent in its last 600 ticks, in ms (null before the first tick). */
  tickCpuMsP99: number | null;
  /** The longest time between two tick starts among its last 600 ticks, in ms: a stall (null before two ticks). */
  tickGapMsMax: number | null;
}

/** Counts a room's ticks and slowdowns on its clock. */
export class RoomPace {
  private readonly clock: Clock;
  private windowStartMs = -1;
  private ticksInWindow = 0;
  private ticksRate = 0;
  private lastSlowdownMs = -Infinity;
  private readonly tickMs = new Float64Array(TICK_TIMES_KEPT);
  private readonly tickCpuMs = new Float64Array(TICK_TIMES_KEPT);
  private readonly gapsMs = new Float64Array(TICK_TIMES_KEPT);
  private gapCount = 0;
  private lastStartMs = -1;
  private tickCount = 0;

  constructor(clock: Clock) {
    this.clock = clock;
  }

  /** One tick ran, taking `tookMs` of wall time and `cpuMs` of its thread's CPU time (default: the wall time). */
  ticked(tookMs: number, cpuMs = tookMs): void {
    this.tickCpuMs[this.tickCount % TICK_TIMES_KEPT] = cpuMs;
    this.tickMs[this.tickCount++ % TICK_TIMES_KEPT] = tookMs;
    const now = this.clock.nowMs();
    const startMs = now - tookMs;
    if (this.lastStartMs >= 0) this.gapsMs[this.gapCount++ % TICK_TIMES_KEPT] = startMs - this.lastStartMs;
    this.lastStartMs = startMs;
    if (this.windowStartMs < 0 || now - this.windowStartMs > 2 * WINDOW_MS) {
      this.windowStartMs = now;
      this.ticksInWindow = 0;
      return;
    }
    this.ticksInWindow++;
    const elapsedMs = now - this.windowStartMs;
    if (elapsedMs >= WINDOW_MS) {
      this.ticksRate = (this.ticksInWindow * 1000) / elapsedMs;
      this.windowStartMs = now;
      this.ticksInWindow = 0;
    }
  }

  /** The room gave up ticks. */
  slowedDown(): void {
    this.lastSlowdownMs = this.clock.nowMs();
  }

  /** Ticks per second and the slow flag alone (no percentiles: cheap enough for every pong). */
  rate(): { ticksPerSecond: number; slow: boolean } {
    const now = this.clock.nowMs();
    const stalled = this.windowStartMs < 0 || now - this.windowStartMs > 2 * WINDOW_MS;
    return { ticksPerSecond: stalled ? 0 : Math.round(this.ticksRate * 10) / 10, slow: now - this.lastSlowdownMs < SLOW_HOLD_MS };
  }

  report(): PaceReport {
    return { ...this.rate(), tickMsP99: this.p99(this.tickMs), tickCpuMsP99: this.p99(this.tickCpuMs), tickGapMsMax: this.maxGap() };
  }

  /** Forgets the gap to the previous tick (the room paused: the time it spent empty is no stall). */
  paused(): void {
    this.lastStartMs = -1;
  }

  private maxGap(): number | null {
    const n = Math.min(this.gapCount, TICK_TIMES_KEPT);
    if (n === 0) return null;
    let max = 0;
    for (let i = 0; i < n; i++) max = Math.max(max, this.gapsMs[i]);
    return Math.round(max * 1000) / 1000;
  }

  private p99(times: Float64Array): number | null {
    const n = Math.min(this.tickCount, TICK_TIMES_KEPT);
    if (n === 0) return null;
    const sorted = times.slice(0, n).sort();
    return Math.round(sorted[Math.min(n - 1, Math.floor(n * 0.99))] * 1000) / 1000;
  }
}
