// Tests of client/app/motion-meter.ts: a key pressed while the own character stands still is measured to the first
// drawn frame that shows it moved, counting frames of later ticks that did not show it; keys while moving, or with
// no character drawn, start nothing.
import { describe, expect, it } from 'vitest';
import { KeyToMotionMeter } from '../../../client/app/motion-meter.ts';

describe('KeyToMotionMeter', () => {
  it('counts the frames and milliseconds from a key to the first frame that shows the character moved', () => {
    const m = new KeyToMotionMeter();
    m.frameDrawn(0, 1, 1, [0, 0, 0]);
    m.frameDrawn(16, 2, 2, [0, 0, 0.001]);
    m.keyDown(20, 2);
    m.frameDrawn(33, 3, 3, [0, 0, 0.003]);
    m.frameDrawn(50, 4, 4, [0, 0, 0.002]);
    expect(m.last).toBeNull();
    m.frameDrawn(66, 5, 5, [0, 0, -0.06]);
    expect(m.last).toEqual({ frames: 3, ms: 46, staleFrames: 2 });
    expect(m.count).toBe(1);
  });

  it('measures a move shown on the very next frame as one frame', () => {
    const m = new KeyToMotionMeter();
    m.frameDrawn(0, 10, 10, [1, 0, 1]);
    m.frameDrawn(16, 11, 11, [1, 0, 1]);
    m.keyDown(18, 11);
    m.frameDrawn(33, 12, 12, [1, 0, 0.9]);
    expect(m.last).toEqual({ frames: 1, ms: 15, staleFrames: 0 });
  });

  it('counts no stale frame for frames that still draw the tick of the key', () => {
    const m = new KeyToMotionMeter();
    m.frameDrawn(0, 1, 40, [0, 0, 0]);
    m.frameDrawn(16, 2, 41, [0, 0, 0]);
    m.keyDown(20, 2);
    m.frameDrawn(25, 3, 41, [0, 0, 0]);
    m.frameDrawn(33, 4, 42, [0, 0, -0.07]);
    expect(m.last).toEqual({ frames: 2, ms: 13, staleFrames: 0 });
  });

  it('starts nothing while the character moves or before one is drawn, and drops a measurement when it vanishes', () => {
    const m = new KeyToMotionMeter();
    m.keyDown(0, 0);
    m.frameDrawn(16, 1, 1, [0, 0, 0]);
    m.frameDrawn(33, 2, 2, [0, 0, 0.5]);
    m.keyDown(40, 2);
    m.frameDrawn(50, 3, 3, [0, 0, 1]);
    expect(m.last).toBeNull();
    m.frameDrawn(66, 4, 4, [0, 0, 1]);
    m.keyDown(70, 4);
    m.frameDrawn(83, 5, 5, null);
    m.frameDrawn(100, 6, 6, [0, 0, 3]);
    expect(m.last).toBeNull();
    expect(m.count).toBe(0);
  });
});
