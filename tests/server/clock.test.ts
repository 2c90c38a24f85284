// Tests for server/clock.ts: the manual clock's timeline and timer order.
import { describe, expect, it } from 'vitest';
import { ManualClock, SystemClock } from '../../server/clock.ts';

describe('ManualClock', () => {
  it('fires timers in due order and shows each timer its own due time', () => {
    const clock = new ManualClock(100);
    const seen: string[] = [];
    clock.setTimer(30, () => seen.push(`b@${clock.nowMs()}`));
    clock.setTimer(10, () => seen.push(`a@${clock.nowMs()}`));
    clock.setTimer(30, () => seen.push(`c@${clock.nowMs()}`));
    clock.advance(20);
    expect(seen).toEqual(['a@110']);
    clock.advance(20);
    expect(seen).toEqual(['a@110', 'b@130', 'c@130']);
    expect(clock.nowMs()).toBe(140);
  });

  it('runs timers scheduled by timers within the same advance', () => {
    const clock = new ManualClock();
    const seen: number[] = [];
    const again = (): void => {
      seen.push(clock.nowMs());
      if (seen.length < 4) clock.setTimer(5, again);
    };
    clock.setTimer(5, again);
    clock.advance(100);
    expect(seen).toEqual([5, 10, 15, 20]);
  });

  it('does not fire a cleared timer', () => {
    const clock = new ManualClock();
    let fired = false;
    const h = clock.setTimer(1, () => (fired = true));
    clock.clearTimer(h);
    clock.advance(10);
    expect(fired).toBe(false);
    expect(clock.pendingTimers()).toBe(0);
  });

  it('rejects going backwards', () => {
    expect(() => new ManualClock().advance(-1)).toThrow(/advance/);
  });
});

describe('SystemClock', () => {
  it('reads monotonic time and runs a timer', async () => {
    const clock = new SystemClock();
    const t0 = clock.nowMs();
    const t1 = await new Promise<number>((resolve) => clock.setTimer(5, () => resolve(clock.nowMs())));
    expect(t1 - t0).toBeGreaterThanOrEqual(4);
  });
});
