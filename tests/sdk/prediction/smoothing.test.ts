// Tests of correction smoothing: a corrected body keeps its on-screen pose at the moment of the correction, the
// offset halves every half-life and then vanishes, and bodies without corrections are drawn where they are.
import { describe, expect, it } from 'vitest';
import { BODY_STATE_STRIDE, BodyFlag } from '../../../shared/physics-data/body-state.ts';
import { CorrectionSmoother, type BodyRead } from '../../../sdk/prediction/smoothing.ts';

function read(poses: Array<[number, number[], number?]>): BodyRead {
  const states = new Float32Array(poses.length * BODY_STATE_STRIDE);
  poses.forEach(([, p], i) => states.set(p, i * BODY_STATE_STRIDE));
  return { count: poses.length, ids: Uint32Array.from(poses.map((p) => p[0])), states, flags: Uint8Array.from(poses.map((p) => p[2] ?? BodyFlag.Dynamic)) };
}

const S = Math.SQRT1_2;

describe('smoothing', () => {
  it('keeps a corrected body where it was drawn, then glides it to the corrected pose', () => {
    const s = new CorrectionSmoother(100);
    const before = s.capture(read([[1, [0, 1, 0, 0, 0, 0, 1]], [2, [5, 0, 0, 0, 0, 0, 1]], [3, [9, 9, 9, 0, 0, 0, 1], BodyFlag.Static]]));
    expect(before.has(3)).toBe(false);
    const after = read([[1, [1, 1, 0, 0, 0, S, S]], [2, [5, 0, 0, 0, 0, 0, 1]]]);
    expect(s.correct(before, after)).toBeCloseTo(1, 6);
    const drawn = s.apply(after).states;
    expect(Array.from(drawn.slice(0, 7)).map((v) => Number(v.toFixed(5)))).toEqual([0, 1, 0, 0, 0, 0, 1]);
    expect(Array.from(drawn.slice(BODY_STATE_STRIDE, BODY_STATE_STRIDE + 3))).toEqual([5, 0, 0]);
    expect(s.activeCount).toBe(1);
    s.decay(100);
    expect(s.apply(after).states[0]).toBeCloseTo(0.5, 5);
    s.decay(2000);
    expect(s.activeCount).toBe(0);
    expect(Array.from(s.apply(after).states.slice(0, 7))).toEqual(Array.from(after.states.slice(0, 7)));
  });
});
