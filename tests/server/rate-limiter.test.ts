// Tests for server/rate-limiter.ts: burst, sustained rate, refill on the injected clock.
import { describe, expect, it } from 'vitest';
import { RateLimiter } from '../../server/rate-limiter.ts';
import { ManualClock } from '../../shared/clock.ts';

describe('RateLimiter', () => {
  it('allows a burst, then refuses until tokens refill', () => {
    const clock = new ManualClock();
    const rl = new RateLimiter(clock, { perSecond: 10, burst: 5 });
    for (let i = 0; i < 5; i++) expect(rl.take()).toBe(true);
    expect(rl.take()).toBe(false);
    clock.advance(100);
    expect(rl.take()).toBe(true);
    expect(rl.take()).toBe(false);
  });

  it('sustains its rate over time but never more', () => {
    const clock = new ManualClock();
    const rl = new RateLimiter(clock, { perSecond: 60, burst: 10 });
    let ok = 0;
    for (let i = 0; i < 1000; i++) {
      if (rl.take()) ok++;
      clock.advance(5); // 200 attempts per second
    }
    expect(ok).toBeGreaterThanOrEqual(300);
    expect(ok).toBeLessThanOrEqual(311);
  });

  it('never stores more than the burst', () => {
    const clock = new ManualClock();
    const rl = new RateLimiter(clock, { perSecond: 100, burst: 3 });
    clock.advance(60_000);
    expect(rl.available()).toBe(3);
  });

  it('rejects bad limits', () => {
    expect(() => new RateLimiter(new ManualClock(), { perSecond: 0, burst: 1 })).toThrow(/perSecond/);
    expect(() => new RateLimiter(new ManualClock(), { perSecond: 1, burst: Number.NaN })).toThrow(/burst/);
  });
});
