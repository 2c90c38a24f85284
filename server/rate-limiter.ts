// A token bucket on an injectable clock: a sustained rate plus a burst allowance, used per client for messages
// and bytes. It only counts; the caller decides what exceeding it means (the session disconnects the client).
import type { Clock } from '../shared/clock.ts';

/** Rate and burst of one bucket. */
export interface RateLimit {
  /** Tokens refilled per second. */
  perSecond: number;
  /** Bucket size: the most tokens spendable at once. */
  burst: number;
}

/** A token bucket: `take(n)` spends n tokens if available. */
export class RateLimiter {
  readonly limit: RateLimit;
  private readonly clock: Clock;
  private tokens: number;
  private lastMs: number;

  constructor(clock: Clock, limit: RateLimit) {
    if (!(limit.perSecond > 0) || !Number.isFinite(limit.perSecond)) throw new Error(`RateLimiter: perSecond must be a positive number, got ${limit.perSecond}`);
    if (!(limit.burst >= 1) || !Number.isFinite(limit.burst)) throw new Error(`RateLimiter: burst must be ≥ 1, got ${limit.burst}`);
    this.clock = clock;
    this.limit = { perSecond: limit.perSecond, burst: limit.burst };
    this.tokens = limit.burst;
    this.lastMs = clock.nowMs();
  }

  /** Tokens available now. */
  available(): number {
    this.refill();
    return this.tokens;
  }

  /** Spends `n` tokens and returns true, or returns false (spending nothing) when fewer are available. */
  take(n = 1): boolean {
    this.refill();
    if (this.tokens < n) return false;
    this.tokens -= n;
    return true;
  }

  private refill(): void {
    const now = this.clock.nowMs();
    const elapsedMs = now - this.lastMs;
    if (elapsedMs > 0) {
      this.tokens = Math.min(this.limit.burst, this.tokens + (elapsedMs * this.limit.perSecond) / 1000);
      this.lastMs = now;
    }
  }
}
