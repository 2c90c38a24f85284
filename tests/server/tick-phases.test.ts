// Tests for server/tick-phases.ts: rooms of one thread get tick phases spread over the period, and phase times.
import { describe, expect, it } from 'vitest';
import { TickClock } from '../../server/tick-clock.ts';
import { nextPhaseTimeMs, TickPhases, workerPhaseOffsetMs } from '../../server/tick-phases.ts';
import { ManualClock } from '../../shared/clock.ts';

describe('TickPhases', () => {
  it('spreads rooms over the period, each new one in the middle of the widest gap', () => {
    const phases = new TickPhases(16);
    expect([phases.take(), phases.take(), phases.take(), phases.take()]).toEqual([0, 8, 4, 12]);
    expect([phases.take(), phases.take(), phases.take(), phases.take()]).toEqual([2, 6, 10, 14]);
    expect(phases.phases).toEqual([0, 2, 4, 6, 8, 10, 12, 14]);
  });

  it('keeps 20 rooms at least 0.5 ms apart in a 16.7 ms period', () => {
    const phases = new TickPhases();
    for (let i = 0; i < 20; i++) phases.take();
    const held = phases.phases;
    for (let i = 1; i < held.length; i++) expect(held[i] - held[i - 1]).toBeGreaterThanOrEqual(0.5);
    expect(held.at(-1)).toBeLessThan(phases.periodMs);
  });

  it('fills the gap a closed room left before splitting narrower ones', () => {
    const phases = new TickPhases(16);
    for (let i = 0; i < 4; i++) phases.take(); // 0, 4, 8, 12
    phases.release(8);
    expect(phases.take()).toBe(8);
    phases.release(99); // unknown: ignored
    expect(phases.phases).toEqual([0, 4, 8, 12]);
  });
});

describe('workerPhaseOffsetMs', () => {
  it("interleaves two workers' rooms on one core: up to 16 rooms each, never two at the same instant", () => {
    const a = new TickPhases(16, workerPhaseOffsetMs(0, 2, 16));
    const b = new TickPhases(16, workerPhaseOffsetMs(1, 2, 16));
    expect([b.take(), b.take(), b.take()]).toEqual([0.5, 8.5, 4.5]);
    for (let i = 0; i < 16; i++) a.take();
    for (let i = 0; i < 13; i++) b.take();
    const all = [...a.phases, ...b.phases].sort((x, y) => x - y);
    expect(new Set(all).size).toBe(32);
    for (let i = 1; i < all.length; i++) expect(all[i] - all[i - 1]).toBeCloseTo(0.5, 9);
    expect(() => workerPhaseOffsetMs(2, 2)).toThrow(/index/);
  });
});

describe('TickPhases with TickClocks', () => {
  it('keeps rooms that slowed down in the same stall apart afterwards, each back on its own phase', () => {
    const clock = new ManualClock(0);
    const phases = new TickPhases();
    const rooms = [0, 1, 2, 3].map(() => new TickClock({ clock, phaseMs: phases.take(), onTick: () => {} }));
    for (const r of rooms) r.start();
    clock.advance(100);
    // One stall hits every room: the loop wakes 300 ms late and polls them one after another.
    for (const r of rooms) r.stop();
    clock.advance(300);
    for (const r of rooms) expect(r.poll()).toBe(1);
    const offsets = rooms.map((r) => (((r.nextDueMs() % phases.periodMs) + phases.periodMs) % phases.periodMs).toFixed(3));
    expect(new Set(offsets).size).toBe(4);
    expect(offsets.map(Number).sort((a, b) => a - b)).toEqual(phases.phases.map((p) => Number(p.toFixed(3))));
    // Without phases the same stall re-anchors them all on the same instant.
    const plain = [0, 1].map(() => new TickClock({ clock, onTick: () => {} }));
    plain.forEach((r) => r.poll());
    clock.advance(300);
    plain.forEach((r) => r.poll());
    expect(plain[0].nextDueMs()).toBe(plain[1].nextDueMs());
  });
});

describe('nextPhaseTimeMs', () => {
  it('finds the first time at or after now on the phase', () => {
    expect(nextPhaseTimeMs(100, 16, 4)).toBe(100);
    expect(nextPhaseTimeMs(100.5, 16, 4)).toBe(116);
    expect(nextPhaseTimeMs(3, 16, 4)).toBe(4);
    expect(nextPhaseTimeMs(0, 16, 0)).toBe(0);
    expect(() => nextPhaseTimeMs(0, 16, 16)).toThrow(/phaseMs/);
  });
});
