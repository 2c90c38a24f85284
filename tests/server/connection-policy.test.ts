// Tests for server/connection-policy.ts on a ManualClock: per-address caps on open and half-open sockets, the global
// cap, counting until the socket is gone, growing refusal after repeated kicks, and forgetting addresses.
import { describe, expect, it } from 'vitest';
import { ManualClock } from '../../shared/clock.ts';
import { ConnectionPolicy, DEFAULT_CONNECTION_POLICY } from '../../server/connection-policy.ts';

describe('ConnectionPolicy', () => {
  it('caps the sockets of one address that have not said hello, and frees a slot on hello', () => {
    const policy = new ConnectionPolicy(new ManualClock(), { maxPendingPerAddress: 2 });
    const a = policy.open('10.0.0.1');
    policy.open('10.0.0.1');
    expect(policy.admit('10.0.0.1')).toMatchObject({ reason: 'address-pending', retryAfterMs: 1000 });
    expect(policy.admit('10.0.0.2')).toBeNull();
    a.helloed();
    a.helloed(); // idempotent
    expect(policy.admit('10.0.0.1')).toBeNull();
    expect(policy.countsOf('10.0.0.1')).toEqual({ sockets: 2, pending: 1, kicks: 0 });
  });

  it('caps the open sockets of one address and counts a socket until it is gone', () => {
    const policy = new ConnectionPolicy(new ManualClock(), { maxSocketsPerAddress: 2 });
    const a = policy.open('10.0.0.1');
    const b = policy.open('10.0.0.1');
    a.helloed();
    b.helloed();
    expect(policy.admit('10.0.0.1')).toMatchObject({ reason: 'address-sockets', message: 'too many connections from your address (2 open)' });
    a.kicked(); // kicked but not yet gone: still counted
    expect(policy.admit('10.0.0.1')?.reason).toBe('address-sockets');
    a.closed();
    a.closed();
    expect(policy.admit('10.0.0.1')).toBeNull();
    expect(policy.openSockets).toBe(1);
  });

  it('refuses everyone past the global cap', () => {
    const policy = new ConnectionPolicy(new ManualClock(), { maxSockets: 3 });
    for (const ip of ['10.0.0.1', '10.0.0.2', '10.0.0.3']) policy.open(ip);
    expect(policy.admit('10.0.0.4')).toMatchObject({ reason: 'server-full' });
  });

  it('refuses an address for a growing period once its clients were kicked too often, then forgets', () => {
    const clock = new ManualClock();
    const policy = new ConnectionPolicy(clock, { kicksBeforeBackoff: 3, backoffBaseMs: 2000, backoffMaxMs: 10_000, kickMemoryMs: 60_000 });
    const kickOnce = (): void => {
      const t = policy.open('10.0.0.9');
      t.kicked();
      t.closed();
    };
    kickOnce();
    kickOnce();
    expect(policy.admit('10.0.0.9')).toBeNull();
    const refusedFor: number[] = [];
    for (let i = 0; i < 5; i++) {
      kickOnce();
      refusedFor.push(policy.admit('10.0.0.9')!.retryAfterMs);
      clock.advance(refusedFor[i]);
    }
    expect(refusedFor).toEqual([2000, 4000, 8000, 10_000, 10_000]);
    expect(policy.admit('10.0.0.9')).toBeNull();
    expect(policy.admit('10.0.0.8')).toBeNull(); // other addresses never noticed
    // A minute without kicks: the slate is clean; the next kick alone refuses nothing.
    clock.advance(60_001);
    kickOnce();
    expect(policy.admit('10.0.0.9')).toBeNull();
    expect(policy.countsOf('10.0.0.9').kicks).toBe(1);
  });

  it('forgets addresses that carry nothing and keeps the table within its cap', () => {
    const clock = new ManualClock();
    const policy = new ConnectionPolicy(clock, { maxTrackedAddresses: 100, kickMemoryMs: 1000 });
    const t = policy.open('10.0.0.1');
    t.closed();
    expect(policy.trackedAddresses).toBe(0);
    for (let i = 0; i < 500; i++) {
      const k = policy.open(`10.1.${i >> 8}.${i & 255}`);
      k.kicked();
      k.closed();
    }
    expect(policy.trackedAddresses).toBeLessThanOrEqual(100);
    clock.advance(1001);
    policy.sweep();
    expect(policy.trackedAddresses).toBe(0);
  });

  it('rejects limits that are not whole numbers', () => {
    expect(() => new ConnectionPolicy(new ManualClock(), { maxSocketsPerAddress: -1 })).toThrow(/maxSocketsPerAddress must be a whole number/);
    expect(() => new ConnectionPolicy(new ManualClock(), { backoffBaseMs: Number.NaN })).toThrow(/backoffBaseMs/);
    expect(new ConnectionPolicy(new ManualClock(), { maxSocketsPerAddress: Infinity }).options.maxPendingPerAddress).toBe(DEFAULT_CONNECTION_POLICY.maxPendingPerAddress);
  });
});
