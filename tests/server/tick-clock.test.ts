// Tests for server/tick-clock.ts: fixed-rate ticks on absolute targets, bounded catch-up, slowdown reports.
import { describe, expect, it } from 'vitest';
import { TickClock, type SlowdownReport } from '../../server/tick-clock.ts';
import { ManualClock } from '../../shared/clock.ts';

describe('TickClock', () => {
  it('runs tick 0 at start and one tick per 1/60 s after', () => {
    const clock = new ManualClock(1234.5);
    const ticks: Array<[number, number]> = [];
    const tc = new TickClock({ clock, onTick: (t) => ticks.push([t, clock.nowMs()]) });
    tc.start();
    clock.advance(0);
    expect(ticks).toEqual([[0, 1234.5]]);
    clock.advance(1000);
    expect(ticks.length).toBe(61);
    expect(ticks.map(([t]) => t)).toEqual(Array.from({ length: 61 }, (_, i) => i));
    expect(ticks[60][1]).toBeCloseTo(2234.5, 6);
  });

  it('does not drift over an hour of irregular wake-ups', () => {
    const clock = new ManualClock();
    let count = 0;
    const tc = new TickClock({ clock, onTick: () => count++ });
    tc.start();
    // Advance one hour in uneven steps (3, 7, 11, 13 ms …): the tick count must equal the ideal count exactly.
    const steps = [3, 7, 11, 13, 17.3, 1.1];
    let elapsed = 0;
    let i = 0;
    while (elapsed < 3_600_000) {
      const step = Math.min(steps[i++ % steps.length], 3_600_000 - elapsed);
      clock.advance(step);
      elapsed += step;
    }
    expect(count).toBe(3600 * 60 + 1);
    expect(tc.slowdowns).toBe(0);
  });

  it('catches up a short stall with back-to-back ticks', () => {
    const clock = new ManualClock();
    let count = 0;
    const tc = new TickClock({ clock, maxCatchUpTicks: 4, onTick: () => count++ });
    tc.start();
    clock.advance(0);
    expect(count).toBe(1);
    // Nothing polls for 3 tick periods (the timer fires late as with a busy event loop): poll runs 3 at once.
    tc.stop();
    clock.advance(50);
    expect(tc.poll()).toBe(3);
    expect(tc.slowdowns).toBe(0);
  });

  it('runs one tick instead of a burst when further behind than the catch-up limit, gives up the rest, and reports it', () => {
    const clock = new ManualClock();
    const reports: SlowdownReport[] = [];
    let count = 0;
    const tc = new TickClock({ clock, maxCatchUpTicks: 4, onTick: () => count++, onSlowdown: (r) => reports.push(r) });
    tc.start();
    clock.advance(0);
    tc.stop();
    clock.advance(1000); // a 1 s stall: 60 ticks overdue
    expect(tc.poll()).toBe(1);
    expect(count).toBe(2);
    expect(reports).toHaveLength(1);
    expect(reports[0].skippedTicks).toBe(59);
    expect(reports[0].lostMs).toBeCloseTo(59 * (1000 / 60), 6);
    // Next tick is due one period later, not immediately: the lost time is not owed any more.
    expect(tc.poll()).toBe(0);
    expect(tc.nextDueMs() - clock.nowMs()).toBeCloseTo(1000 / 60, 6);
    // Restarting re-anchors on now: the next tick runs at once, then 60 per second, with nothing owed.
    tc.start();
    clock.advance(1000);
    expect(count).toBe(63);
    expect(tc.slowdowns).toBe(1);
  });

  it('still catches up a stall within the limit, so a brief pause costs no ticks', () => {
    const clock = new ManualClock();
    let count = 0;
    const tc = new TickClock({ clock, maxCatchUpTicks: 4, onTick: () => count++ });
    tc.poll();
    clock.advance(4 * (1000 / 60));
    expect(tc.poll()).toBe(4);
    expect(count).toBe(5);
    expect(tc.slowdowns).toBe(0);
  });

  it('ticks on its phase of the period: the first tick waits for it and a slowdown returns to it', () => {
    const period = 1000 / 60;
    const clock = new ManualClock(1000);
    const starts: number[] = [];
    const tc = new TickClock({ clock, phaseMs: 5, onTick: () => starts.push(clock.nowMs()) });
    tc.start();
    clock.advance(period * 3);
    // 1000 ms is 60 whole periods: the phase-5 slots are 1005, 1021.67, 1038.33 …
    expect(starts.length).toBe(3);
    starts.forEach((t, i) => expect(t).toBeCloseTo(1005 + i * period, 6));
    tc.stop();
    clock.advance(500); // far behind: one tick now, then back on the phase at least half a period later
    expect(tc.poll()).toBe(1);
    const due = tc.nextDueMs();
    expect(due - clock.nowMs()).toBeGreaterThanOrEqual(period / 2 - 1e-6);
    expect(due - clock.nowMs()).toBeLessThan(period * 1.5);
    const periods = (due - 5) / period;
    expect(Math.abs(periods - Math.round(periods))).toBeLessThan(1e-6);
    expect(() => new TickClock({ clock, phaseMs: period, onTick: () => {} })).toThrow(/phaseMs/);
  });

  it('slows down steadily when every tick takes two periods', () => {
    const clock = new ManualClock();
    let count = 0;
    const tc = new TickClock({
      clock,
      maxCatchUpTicks: 3,
      onTick: () => {
        count++;
      },
    });
    // Ticks that cost 2 periods each: poll by hand and advance time by what the ticks cost.
    for (let i = 0; i < 100; i++) {
      const ran = tc.poll();
      clock.advance((ran * 2000) / 60 + 1);
    }
    // About half real time, never more than the catch-up limit per wake-up, and slowdowns reported.
    expect(count).toBeLessThan(400);
    expect(tc.slowdowns).toBeGreaterThan(10);
  });

  it('stops and hands the error on when a tick throws', () => {
    const clock = new ManualClock();
    const errors: unknown[] = [];
    const tc = new TickClock({
      clock,
      onTick: (t) => {
        if (t === 2) throw new Error('boom');
      },
      onError: (e) => errors.push(e),
    });
    tc.start();
    clock.advance(100);
    expect(errors).toHaveLength(1);
    expect(tc.isRunning).toBe(false);
    expect(tc.ticksRun).toBe(3);
  });

  it('rejects invalid rates', () => {
    expect(() => new TickClock({ clock: new ManualClock(), tickRateHz: 0, onTick: () => {} })).toThrow(/tickRateHz/);
    expect(() => new TickClock({ clock: new ManualClock(), maxCatchUpTicks: 0, onTick: () => {} })).toThrow(/maxCatchUpTicks/);
  });
});
