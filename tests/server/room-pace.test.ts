// Tests for server/room-pace.ts: ticks per second over the last second, 0 once ticks stop, and the slow flag's hold.
import { describe, expect, it } from 'vitest';
import { RoomPace, SLOW_HOLD_MS } from '../../server/room-pace.ts';
import { ManualClock } from '../../shared/clock.ts';
import { TICK_MS } from '../../shared/tick-rate.ts';

describe('RoomPace', () => {
  it('reports the ticks run over the last second, and 0 once they stop', () => {
    const clock = new ManualClock();
    const pace = new RoomPace(clock);
    for (let i = 0; i < 130; i++) {
      pace.ticked(1);
      clock.advance(TICK_MS);
    }
    expect(pace.report().ticksPerSecond).toBeCloseTo(60, 0);
    for (let i = 0; i < 70; i++) {
      pace.ticked(2);
      clock.advance(TICK_MS * 2);
    }
    expect(pace.report().ticksPerSecond).toBeCloseTo(30, 0);
    clock.advance(3000);
    expect(pace.report()).toMatchObject({ ticksPerSecond: 0, slow: false, tickMsP99: 2, tickCpuMsP99: 2 });
  });

  it('reports the 99th percentile of the last 600 tick times', () => {
    const pace = new RoomPace(new ManualClock());
    expect(pace.report().tickMsP99).toBeNull();
    for (let i = 0; i < 1000; i++) pace.ticked(i < 400 ? 50 : (i % 100) / 10);
    expect(pace.report().tickMsP99).toBe(9.9);
  });

  it('reports the longest time between two tick starts, not counting a pause', () => {
    const clock = new ManualClock();
    const pace = new RoomPace(clock);
    expect(pace.report().tickGapMsMax).toBeNull();
    for (let i = 0; i < 10; i++) {
      clock.advance(i === 5 ? 120 : TICK_MS);
      pace.ticked(1);
    }
    expect(pace.report().tickGapMsMax).toBeCloseTo(120, 6);
    pace.paused();
    clock.advance(60_000);
    pace.ticked(1);
    expect(pace.report().tickGapMsMax).toBeCloseTo(120, 6);
  });

  it('says slow from a slowdown until SLOW_HOLD_MS pass without another', () => {
    const clock = new ManualClock();
    const pace = new RoomPace(clock);
    expect(pace.report().slow).toBe(false);
    pace.slowedDown();
    clock.advance(SLOW_HOLD_MS - 1);
    expect(pace.report().slow).toBe(true);
    clock.advance(2);
    expect(pace.report().slow).toBe(false);
  });
});
