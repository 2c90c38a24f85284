// Tests of client/app/motion-meter.ts: a key pressed while the own character stands still is measured to the first
// drawn frame that shows it moved, counting the frames that drew a world which had run the key's tick without the
// move; keys while moving, or with no character drawn, start nothing.
import { describe, expect, it } from 'vitest';
import { KeyToMotionMeter } from '../../../client/app/motion-meter.ts';

describe('KeyToMotionMeter', () => {
  it('counts the frames and milliseconds from a key to the first frame that shows the character moved', () => {
    const m = new KeyToMotionMeter();
    m.frameDrawn(0, 1, 100, -2, [0, 0, 0]);
    m.frameDrawn(16, 2, 101, -2, [0, 0, 0.001]);
    m.keyDown(20, 2, 104);
    m.frameDrawn(33, 3, 102, -2, [0, 0, 0.003]);
    m.frameDrawn(50, 4, 103, -2, [0, 0, 0.002]);
    expect(m.last).toBeNull();
    m.frameDrawn(66, 5, 105, -2, [0, 0, -0.06]);
    expect(m.last).toEqual({ frames: 3, ms: 46, staleFrames: 0, keyTick: 104, shownAfterTicks: 105, shownAheadOfServerTicks: -2 });
    expect(m.count).toBe(1);
  });

  it('measures a move shown on the very next frame as one frame', () => {
    const m = new KeyToMotionMeter();
    m.frameDrawn(0, 10, 50, -2, [1, 0, 1]);
    m.frameDrawn(16, 11, 51, -2, [1, 0, 1]);
    m.keyDown(18, 11, 51);
    m.frameDrawn(33, 12, 52, -2, [1, 0, 0.9]);
    expect(m.last).toEqual({ frames: 1, ms: 15, staleFrames: 0, keyTick: 51, shownAfterTicks: 52, shownAheadOfServerTicks: -2 });
  });

  it("counts as stale the frames whose world had run the key's tick without showing the move", () => {
    const m = new KeyToMotionMeter();
    m.frameDrawn(0, 1, 40, -2, [0, 0, 0]);
    m.frameDrawn(16, 2, 40.5, -2, [0, 0, 0]);
    m.keyDown(20, 2, 42);
    m.frameDrawn(25, 3, 42.5, -2, [0, 0, 0]);
    m.frameDrawn(33, 4, 43, -2, [0, 0, 0]);
    m.frameDrawn(50, 5, 44, -2, [0, 0, 0]);
    m.frameDrawn(66, 6, 45, -2, [0, 0, -0.07]);
    expect(m.last).toEqual({ frames: 4, ms: 46, staleFrames: 2, keyTick: 42, shownAfterTicks: 45, shownAheadOfServerTicks: -2 });
  });

  it('starts nothing while the character moves or before one is drawn, and drops a measurement when it vanishes', () => {
    const m = new KeyToMotionMeter();
    m.keyDown(0, 0, 1);
    m.frameDrawn(16, 1, 1, -2, [0, 0, 0]);
    m.frameDrawn(33, 2, 2, -2, [0, 0, 0.5]);
    m.keyDown(40, 2, 3);
    m.frameDrawn(50, 3, 3, -2, [0, 0, 1]);
    expect(m.last).toBeNull();
    m.frameDrawn(66, 4, 4, -2, [0, 0, 1]);
    m.keyDown(70, 4, 5);
    m.frameDrawn(83, 5, 5, -2, null);
    m.frameDrawn(100, 6, 6, -2, [0, 0, 3]);
    expect(m.last).toBeNull();
    expect(m.count).toBe(0);
  });
});
