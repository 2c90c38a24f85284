// Tests for server/monitor/rate-meter.ts: per-second slope of a cumulative counter over a 5 s window.
import { describe, expect, it } from 'vitest';
import { RateMeter } from '../../../server/monitor/rate-meter.ts';

describe('rate-meter', () => {
  it('is 0 until two samples exist, then the slope per second', () => {
    const m = new RateMeter();
    expect(m.perSecond()).toBe(0);
    m.sample(1000, 500);
    expect(m.perSecond()).toBe(0);
    m.sample(2000, 1500);
    expect(m.perSecond()).toBe(1000);
  });

  it('forgets samples older than the window, so a stopped counter falls to 0', () => {
    const m = new RateMeter();
    for (let t = 0; t <= 3000; t += 1000) m.sample(t, t * 2);
    expect(m.perSecond()).toBe(2000);
    for (let t = 4000; t <= 10_000; t += 1000) m.sample(t, 6000);
    expect(m.perSecond()).toBe(0);
  });
});
