// Tests for sdk/clock.ts: the client library's real clock reads monotonic time, runs timers and cancels them.
import { describe, expect, it } from 'vitest';
import { RealClock } from '../../sdk/clock.ts';

describe('RealClock', () => {
  it('reads monotonic time and runs a timer', async () => {
    const clock = new RealClock();
    const t0 = clock.nowMs();
    const t1 = await new Promise<number>((resolve) => clock.setTimer(5, () => resolve(clock.nowMs())));
    expect(t1 - t0).toBeGreaterThanOrEqual(4);
  });

  it('does not run a cleared timer', async () => {
    const clock = new RealClock();
    let fired = false;
    clock.clearTimer(clock.setTimer(1, () => (fired = true)));
    await new Promise<void>((resolve) => clock.setTimer(20, resolve));
    expect(fired).toBe(false);
  });
});
