// Tests for shared/clock.ts: the manual clock's timeline and timer order, and TimerClock's handles over platform timers.
import { describe, expect, it } from 'vitest';
import { ManualClock, TimerClock, type TimerSource } from '../../shared/clock.ts';

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

describe('TimerClock', () => {
  /** A platform stand-in that records what the clock asked of it. */
  function fakeSource(): TimerSource<string> & { started: Array<{ token: string; delayMs: number; fn: () => void }>; cancelled: string[]; nowMs: number } {
    const src = {
      started: [] as Array<{ token: string; delayMs: number; fn: () => void }>,
      cancelled: [] as string[],
      nowMs: 42,
      now: () => src.nowMs,
      start(delayMs: number, fn: () => void): string {
        const token = `t${src.started.length}`;
        src.started.push({ token, delayMs, fn });
        return token;
      },
      cancel(token: string): void {
        src.cancelled.push(token);
      },
    };
    return src;
  }

  it('reads the platform time and clamps a negative delay to zero', () => {
    const src = fakeSource();
    const clock = new TimerClock(src);
    expect(clock.nowMs()).toBe(42);
    clock.setTimer(-5, () => {});
    expect(src.started[0]!.delayMs).toBe(0);
  });

  it('cancels the platform timer behind a handle once, and not after it ran', () => {
    const src = fakeSource();
    const clock = new TimerClock(src);
    const seen: string[] = [];
    const a = clock.setTimer(10, () => seen.push('a'));
    const b = clock.setTimer(20, () => seen.push('b'));
    expect(a.id).not.toBe(b.id);
    clock.clearTimer(a);
    clock.clearTimer(a);
    expect(src.cancelled).toEqual(['t0']);
    src.started[1]!.fn();
    clock.clearTimer(b);
    expect(seen).toEqual(['b']);
    expect(src.cancelled).toEqual(['t0']);
  });
});
