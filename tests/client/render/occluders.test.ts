// Tests of the camera's wall check: ray casts against static oriented boxes.
import { describe, expect, it } from 'vitest';
import { BoxOccluders } from '../../../client/render/occluders.ts';

const I = { x: 0, y: 0, z: 0, w: 1 };

describe('BoxOccluders', () => {
  it('reports the fraction where a segment first enters a box', () => {
    const o = new BoxOccluders();
    o.set(1, { x: 5, y: 0, z: 0 }, I, { x: 1, y: 1, z: 1 });
    o.set(2, { x: 8, y: 0, z: 0 }, I, { x: 1, y: 1, z: 1 });
    expect(o.castRay([0, 0, 0], [10, 0, 0])).toBeCloseTo(0.4, 9);
    expect(o.castRay([0, 0, 0], [3, 0, 0])).toBe(1);
    expect(o.castRay([0, 2, 0], [10, 2, 0])).toBe(1); // passes over the boxes
  });

  it('honours the box rotation', () => {
    const o = new BoxOccluders();
    // A thin wall 4 m long along X, turned 90° about Y so it runs along Z.
    const s = Math.SQRT1_2;
    o.set(1, { x: 0, y: 0, z: 0 }, { x: 0, y: s, z: 0, w: s }, { x: 2, y: 1, z: 0.1 });
    expect(o.castRay([-5, 0, 1.5], [5, 0, 1.5])).toBeCloseTo(0.49, 6); // crosses the wall at x = −0.1
    expect(o.castRay([-5, 0, 3], [5, 0, 3])).toBe(1); // beyond its end
  });

  it('ignores a box the segment starts in, and forgets deleted boxes', () => {
    const o = new BoxOccluders();
    o.set(1, { x: 0, y: 0, z: 0 }, I, { x: 1, y: 1, z: 1 });
    expect(o.castRay([0, 0, 0], [5, 0, 0])).toBe(1);
    expect(o.castRay([-5, 0, 0], [5, 0, 0])).toBeCloseTo(0.4, 9);
    o.delete(1);
    expect(o.castRay([-5, 0, 0], [5, 0, 0])).toBe(1);
  });
});
