// Tests of the renderer's matrix helpers: WebGPU depth range, look-at orientation, products, quaternion rotation.
import { describe, expect, it } from 'vitest';
import { mat4Identity, mat4LookAt, mat4Multiply, mat4Perspective, mat4TransformPoint, quatRotate } from '../../../client/render/mat4.ts';

const round = (v: number[]): number[] => v.map((x) => Math.round(x * 1e5) / 1e5 + 0);

describe('mat4', () => {
  it('maps the near plane to depth 0 and the far plane to depth 1', () => {
    const p = mat4Perspective(Math.PI / 2, 16 / 9, 0.5, 100);
    expect(mat4TransformPoint(p, [0, 0, -0.5])[2]).toBeCloseTo(0, 6);
    expect(mat4TransformPoint(p, [0, 0, -100])[2]).toBeCloseTo(1, 6);
    // 90° vertical field of view: a point at 45° up lands on the top edge.
    expect(mat4TransformPoint(p, [0, 10, -10])[1]).toBeCloseTo(1, 6);
  });

  it('puts the target straight ahead (−Z) and keeps up as +Y', () => {
    const v = mat4LookAt([10, 5, 3], [10, 5, -7], [0, 1, 0]);
    expect(round(mat4TransformPoint(v, [10, 5, -7]))).toEqual([0, 0, -10]);
    expect(round(mat4TransformPoint(v, [10, 6, 3]))).toEqual([0, 1, 0]);
    expect(round(mat4TransformPoint(v, [11, 5, 3]))).toEqual([1, 0, 0]);
  });

  it('still builds a view when looking straight down', () => {
    const v = mat4LookAt([0, 10, 0], [0, 0, 0], [0, 1, 0]);
    expect(round(mat4TransformPoint(v, [0, 0, 0]))).toEqual([0, 0, -10]);
  });

  it('multiplies so that (a·b)·p = a·(b·p)', () => {
    const a = mat4Perspective(1, 1.5, 0.1, 50);
    const b = mat4LookAt([1, 2, 3], [0, 0, 0], [0, 1, 0]);
    const p: [number, number, number] = [0.3, -0.2, 0.4];
    const ab = mat4Multiply(a, b);
    const viaB = mat4TransformPoint(b, p);
    expect(round(mat4TransformPoint(ab, p))).toEqual(round(mat4TransformPoint(a, viaB)));
    expect(Array.from(mat4Multiply(mat4Identity(), b))).toEqual(Array.from(b));
  });

  it('rotates vectors by a quaternion', () => {
    const s = Math.SQRT1_2;
    expect(round(quatRotate(0, s, 0, s, [1, 0, 0]))).toEqual([0, 0, -1]); // +90° about Y
    expect(round(quatRotate(0, 0, 0, 1, [1, 2, 3]))).toEqual([1, 2, 3]);
  });

  it('rejects impossible projections', () => {
    expect(() => mat4Perspective(0, 1, 0.1, 10)).toThrow(/fovY/);
    expect(() => mat4Perspective(1, 0, 0.1, 10)).toThrow(/aspect/);
    expect(() => mat4Perspective(1, 1, 10, 1)).toThrow(/near < far/);
    expect(() => mat4LookAt([1, 1, 1], [1, 1, 1], [0, 1, 0])).toThrow(/coincide/);
  });
});
