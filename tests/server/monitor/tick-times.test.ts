// Tests for server/monitor/tick-times.ts: nearest-rank p50/p99 over the last 240 ticks, and the running count.
import { describe, expect, it } from 'vitest';
import { TICK_TIMES_WINDOW, TickTimes } from '../../../server/monitor/tick-times.ts';

describe('tick-times', () => {
  it('gives no percentiles before the first tick', () => {
    expect(new TickTimes().percentiles()).toBeNull();
  });

  it('gives the median and the 99th percentile of the recent ticks, forgetting older ones', () => {
    const t = new TickTimes();
    for (let i = 1; i <= 100; i++) t.record(i);
    expect(t.percentiles()).toEqual({ p50Ms: 50, p99Ms: 99 });
    for (let i = 0; i < TICK_TIMES_WINDOW; i++) t.record(2);
    expect(t.percentiles()).toEqual({ p50Ms: 2, p99Ms: 2 });
    expect(t.count).toBe(100 + TICK_TIMES_WINDOW);
  });
});
