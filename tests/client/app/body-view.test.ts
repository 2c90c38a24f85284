// Tests of client/app/body-view.ts: a bulk body read becomes the SnapshotView the world view draws, moving bodies
// only, with poses copied and bodies that are not active marked at rest.
import { describe, expect, it } from 'vitest';
import { viewFromBodyStates } from '../../../client/app/body-view.ts';
import { BODY_STATE_STRIDE, BodyFlag } from '../../../shared/physics-data/body-state.ts';

describe('viewFromBodyStates', () => {
  it('keeps the moving bodies in id order with their poses, leaves statics out and marks sleeping bodies at rest', () => {
    const states = new Float32Array(3 * BODY_STATE_STRIDE);
    states.set([1, 2, 3, 0, 0, 0, 1], 0);
    states.set([9, 9, 9, 0, 0, 0, 1], BODY_STATE_STRIDE);
    states.set([4, 5, 6, 0, 0.6, 0, 0.8], 2 * BODY_STATE_STRIDE);
    const read = { count: 3, ids: Uint32Array.of(2, 5, 7), states, flags: Uint8Array.of(BodyFlag.Dynamic | BodyFlag.Active, BodyFlag.Static, BodyFlag.Dynamic) };
    const view = viewFromBodyStates(12, read, []);
    expect(view.tick).toBe(12);
    expect([...view.ids]).toEqual([2, 7]);
    expect([...view.positions]).toEqual([1, 2, 3, 4, 5, 6]);
    expect([...view.rotations].map((v) => Math.round(v * 10) / 10)).toEqual([0, 0, 0, 1, 0, 0.6, 0, 0.8]);
    expect([...view.atRest]).toEqual([0, 1]);
    states[0] = 100;
    expect(view.positions[0]).toBe(1);
  });
});
