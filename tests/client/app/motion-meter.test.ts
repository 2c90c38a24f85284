// Tests of client/app/motion-meter.ts: a key pressed while the own character stands still is measured to the first
// drawn frame that shows it moved; keys while moving, or with no character drawn, start nothing.
import { describe, expect, it } from 'vitest';
import { KeyToMotionMeter } from '../../../client/app/motion-meter.ts';

describe('KeyToMotionMeter', () => {
  it('counts the frames and milliseconds from a key to the first frame that shows the character moved', () => {
    const m = new KeyToMotionMeter();
    m.frameDrawn(0, 1, [0, 0, 0]);
    m.frameDrawn(16, 2, [0, 0, 0.001]);
    m.keyDown(20, 2);
    m.frameDrawn(33, 3, [0, 0, 0.003]);
    m.frameDrawn(50, 4, [0, 0, 0.002]);
    expect(m.last).toBeNull();
    m.frameDrawn(66, 5, [0, 0, -0.06]);
    expect(m.last).toEqual({ frames: 3, ms: 46 });
    expect(m.count).toBe(1);
  });

  it('measures a move shown on the very next frame as one frame', () => {
    const m = new KeyToMotionMeter();
    m.frameDrawn(0, 10, [1, 0, 1]);
    m.frameDrawn(16, 11, [1, 0, 1]);
    m.keyDown(18, 11);
    m.frameDrawn(33, 12, [1, 0, 0.9]);
    expect(m.last).toEqual({ frames: 1, ms: 15 });
  });

  it('starts nothing while the character moves or before one is drawn, and drops a measurement when it vanishes', () => {
    const m = new KeyToMotionMeter();
    m.keyDown(0, 0);
    m.frameDrawn(16, 1, [0, 0, 0]);
    m.frameDrawn(33, 2, [0, 0, 0.5]);
    m.keyDown(40, 2);
    m.frameDrawn(50, 3, [0, 0, 1]);
    expect(m.last).toBeNull();
    m.frameDrawn(66, 4, [0, 0, 1]);
    m.keyDown(70, 4);
    m.frameDrawn(83, 5, null);
    m.frameDrawn(100, 6, [0, 0, 3]);
    expect(m.last).toBeNull();
    expect(m.count).toBe(0);
  });
});
