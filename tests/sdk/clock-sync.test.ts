// Tests of clock sync: RTT and jitter from pongs, the offset from the least-delayed sample, and the server tick
// estimate converging within a fraction of a tick despite asymmetric queueing and random tick phases.
import { describe, expect, it } from 'vitest';
import { ClockSync } from '../../sdk/clock-sync.ts';
import { Prng } from '../../shared/sim/prng.ts';
import { TICK_MS } from '../../shared/tick-rate.ts';


/** A server whose clock runs `offsetMs` ahead of ours and whose tick n completes at server time anchor + n·TICK_MS. */
function pong(localSendMs: number, upMs: number, downMs: number, offsetMs: number, anchorMs: number): { sentLocalMs: number; receivedLocalMs: number; serverTick: number; serverTimeMs: number } {
  const serverTimeMs = localSendMs + upMs + offsetMs;
  return { sentLocalMs: localSendMs, receivedLocalMs: localSendMs + upMs + downMs, serverTick: Math.floor((serverTimeMs - anchorMs) / TICK_MS), serverTimeMs };
}

describe('clock-sync', () => {
  it('estimates the server tick within a quarter of a tick from ten clean pongs', () => {
    const sync = new ClockSync({ tickRateHz: 60 });
    const offset = 123456.7;
    const anchor = 5000.3;
    for (let i = 0; i < 10; i++) sync.addSample(pong(1000 + i * 97.3, 40, 40, offset, anchor));
    const now = 3000;
    const truth = (now + offset - anchor) / TICK_MS;
    // The tick phase comes from the sample taken closest after a tick boundary.
    expect(Math.abs(sync.serverTickAt(now) - truth)).toBeLessThan(0.25);
    expect(sync.rttMs).toBeCloseTo(80, 6);
    expect(sync.jitterMs).toBe(0);
    expect(sync.offsetMs).toBeCloseTo(offset, 6);
  });

  it('takes the offset from the lowest-RTT sample when queueing delays are one-sided', () => {
    const sync = new ClockSync({ tickRateHz: 60 });
    const rng = new Prng(1);
    const offset = -500;
    const anchor = 0;
    for (let i = 0; i < 12; i++) {
      // The uplink queues up to 60 ms extra; one sample in the window is clean.
      const up = 25 + (i === 7 ? 0 : rng.range(5, 60));
      sync.addSample(pong(i * 1000 + rng.range(0, 16), up, 25, offset, anchor));
    }
    expect(sync.offsetMs).toBeCloseTo(offset, 6);
    expect(sync.minRttMs).toBeCloseTo(50, 6);
    expect(sync.jitterMs).toBeGreaterThan(10);
    const now = 20000;
    expect(Math.abs(sync.serverTickAt(now) - (now + offset - anchor) / TICK_MS)).toBeLessThan(0.5);
  });

  it('starts from the welcome and ignores samples with a negative RTT or non-finite fields', () => {
    const sync = new ClockSync({ tickRateHz: 60 });
    expect(sync.ready).toBe(false);
    expect(() => sync.serverTickAt(0)).toThrow(/no estimate yet/);
    sync.seed(600, 10000);
    expect(sync.serverTickAt(10000 + 1000)).toBeCloseTo(660, 6);
    expect(sync.addSample({ sentLocalMs: 50, receivedLocalMs: 40, serverTick: 1, serverTimeMs: 1 })).toBe(false);
    expect(sync.addSample({ sentLocalMs: 50, receivedLocalMs: 60, serverTick: 1, serverTimeMs: Number.NaN })).toBe(false);
    expect(sync.rejectedSamples).toBe(2);
    expect(sync.rttMs).toBeNull();
  });

  it('maps ticks back to local times consistently', () => {
    const sync = new ClockSync({ tickRateHz: 60 });
    sync.addSample(pong(100, 30, 30, 1000, 200));
    const t = sync.localTimeOfTick(500);
    expect(sync.serverTickAt(t)).toBeCloseTo(500, 9);
  });

  it('follows a server that fell behind once the window forgets the old phase', () => {
    const sync = new ClockSync({ tickRateHz: 60, windowSize: 4 });
    for (let i = 0; i < 4; i++) sync.addSample(pong(i * 1000, 20, 20, 0, 0));
    // The server stalls for 10 ticks: its anchor moves 10 ticks later.
    for (let i = 4; i < 8; i++) sync.addSample(pong(i * 1000, 20, 20, 0, 10 * TICK_MS));
    expect(sync.serverTickAt(9000)).toBeCloseTo((9000 - 10 * TICK_MS) / TICK_MS, 0);
  });

  it('follows a server that runs slow at the next pong, not once the window forgets', () => {
    // A room slowed by load: between pongs a second apart it runs 45 ticks instead of 60, so each pong's anchor is
    // 15 ticks later than the one before. Inputs aimed by an estimate 12 pongs old would be 180 ticks too far ahead.
    const sync = new ClockSync({ tickRateHz: 60 });
    let anchor = 0;
    for (let i = 0; i < 12; i++) {
      sync.addSample(pong(i * 1000, 20, 20, 0, anchor));
      if (i < 11) anchor += 15 * TICK_MS;
    }
    const now = 11_100;
    expect(Math.abs(sync.serverTickAt(now) - (now - anchor) / TICK_MS)).toBeLessThan(1);
  });
});
