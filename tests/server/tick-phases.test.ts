// Tests for server/tick-phases.ts: rooms of one thread get tick phases spread over the period, and phase times.
import { describe, expect, it } from 'vitest';
import { nextPhaseTimeMs, TickPhases } from '../../server/tick-phases.ts';

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

describe('nextPhaseTimeMs', () => {
  it('finds the first time at or after now on the phase', () => {
    expect(nextPhaseTimeMs(100, 16, 4)).toBe(100);
    expect(nextPhaseTimeMs(100.5, 16, 4)).toBe(116);
    expect(nextPhaseTimeMs(3, 16, 4)).toBe(4);
    expect(nextPhaseTimeMs(0, 16, 0)).toBe(0);
    expect(() => nextPhaseTimeMs(0, 16, 16)).toThrow(/phaseMs/);
  });
});
