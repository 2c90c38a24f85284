// Tests for server/clock.ts: the server's real clock reads monotonic time and runs timers on Node.
import { describe, expect, it } from 'vitest';
import { SystemClock } from '../../server/clock.ts';

describe('SystemClock', () => {
  it('reads monotonic time and runs a timer', async () => {
    const clock = new SystemClock();
    const t0 = clock.nowMs();
    const t1 = await new Promise<number>((resolve) => clock.setTimer(5, () => resolve(clock.nowMs())));
    expect(t1 - t0).toBeGreaterThanOrEqual(4);
  });
});
