// Tests of the reconnect policy: exponential backoff with bounded jitter, caps, and which endings are retried.
import { describe, expect, it } from 'vitest';
import { backoffDelayMs, isRetryable, reconnectPolicy } from '../../sdk/reconnect-policy.ts';
import { ByeReason, ErrorCode } from '../../shared/protocol/opcodes.ts';

describe('reconnect-policy', () => {
  it('doubles the delay per attempt up to the cap, scaled by a jitter factor in [0.75, 1.25)', () => {
    const p = reconnectPolicy({ baseDelayMs: 100, maxDelayMs: 1000 });
    expect([1, 2, 3, 4, 5, 9].map((n) => backoffDelayMs(p, n, () => 0.5))).toEqual([100, 200, 400, 800, 1000, 1000]);
    expect(backoffDelayMs(p, 1, () => 0)).toBe(75);
    expect(backoffDelayMs(p, 1, () => 0.999999)).toBe(125);
  });

  it('retries drops and timeouts but not shutdowns, full rooms, kicks, floods, version or room errors', () => {
    expect(isRetryable(null, null)).toBe(true);
    expect(isRetryable(ByeReason.Timeout, null)).toBe(true);
    expect(isRetryable(ByeReason.ServerShutdown, null)).toBe(false);
    expect(isRetryable(ByeReason.RoomFull, null)).toBe(false);
    expect(isRetryable(ByeReason.ServerFull, null)).toBe(false);
    expect(isRetryable(ByeReason.Kicked, null)).toBe(false);
    expect(isRetryable(ByeReason.RoomClosed, null)).toBe(false);
    expect(isRetryable(ByeReason.Flood, null)).toBe(false);
    expect(isRetryable(null, ErrorCode.VersionMismatch)).toBe(false);
    expect(isRetryable(null, ErrorCode.RoomNotFound)).toBe(false);
    expect(isRetryable(null, ErrorCode.ServerFull)).toBe(false);
    expect(isRetryable(null, ErrorCode.RoomFull)).toBe(false);
    expect(isRetryable(null, ErrorCode.RateLimited)).toBe(true);
  });

  it('checks its settings', () => {
    expect(reconnectPolicy(false).enabled).toBe(false);
    expect(() => reconnectPolicy({ maxAttempts: -1 })).toThrow(/maxAttempts/);
    expect(() => reconnectPolicy({ baseDelayMs: 10, maxDelayMs: 5 })).toThrow(/baseDelayMs/);
  });
});
