// Tests of shared/physics-data/shape-spec.ts: every kind of shape validates as plain data (no Jolt loaded), bad
// descriptions are refused with the field named, and compound parts must be convex.
import { describe, expect, it } from 'vitest';
import { checkQuat, checkVec3, validateShapeSpec, type ShapeSpec } from '../../../shared/physics-data/shape-spec.ts';

const GOOD: ShapeSpec[] = [
  { kind: 'box', halfExtents: { x: 1, y: 0.5, z: 2 } },
  { kind: 'sphere', radius: 0.5 },
  { kind: 'capsule', halfHeight: 0.6, radius: 0.3 },
  { kind: 'cylinder', halfHeight: 1, radius: 0.4 },
  { kind: 'convexHull', points: [0, 0, 0, 1, 0, 0, 0, 1, 0, 0, 0, 1] },
  { kind: 'mesh', positions: [0, 0, 0, 1, 0, 0, 0, 0, 1], indices: [0, 2, 1] },
  { kind: 'heightField', heights: [0, 0, 0, 1], sampleCount: 2, cellSize: 1, originXz: { x: -1, z: -1 } },
  { kind: 'compound', parts: [{ shape: { kind: 'sphere', radius: 1 }, position: { x: 0, y: 1, z: 0 }, rotation: { x: 0, y: 0, z: 0, w: 1 } }] },
];

describe('validateShapeSpec', () => {
  it('accepts a well-formed shape of every kind', () => {
    for (const spec of GOOD) expect(() => validateShapeSpec(spec), spec.kind).not.toThrow();
  });

  it('refuses bad sizes, counts and indices, naming the shape and the field', () => {
    expect(() => validateShapeSpec({ kind: 'sphere', radius: 0 }, 'ball')).toThrow(/^ball: radius must be > 0, got 0$/);
    expect(() => validateShapeSpec({ kind: 'box', halfExtents: { x: 1, y: Number.NaN, z: 1 } })).toThrow(/halfExtents\.y must be a finite number/);
    expect(() => validateShapeSpec({ kind: 'convexHull', points: [0, 0, 0, 1, 0, 0, 0, 1, 0] })).toThrow(/at least 4 points, got 3/);
    expect(() => validateShapeSpec({ kind: 'mesh', positions: [0, 0, 0, 1, 0, 0, 0, 0, 1], indices: [0, 1, 3] })).toThrow(/indices\[2\] = 3 is out of range/);
    expect(() => validateShapeSpec({ kind: 'mesh', positions: [0, 0, 0, 1, 0, 0, 2, 0, 0], indices: [0, 1, 2] })).toThrow(/triangle 0 is degenerate/);
    expect(() => validateShapeSpec({ kind: 'heightField', heights: [0, 0, 0], sampleCount: 2, cellSize: 1 })).toThrow(/sampleCount² = 4 samples, got 3/);
    expect(() => validateShapeSpec({ kind: 'cone' } as unknown as ShapeSpec)).toThrow(/unknown shape kind "cone"/);
  });

  it('allows only convex parts in a compound', () => {
    const mesh: ShapeSpec = { kind: 'mesh', positions: [0, 0, 0, 1, 0, 0, 0, 0, 1], indices: [0, 2, 1] };
    expect(() => validateShapeSpec({ kind: 'compound', parts: [{ shape: mesh }] })).toThrow(/^shape part 0: a compound part must be a convex shape, not mesh$/);
    expect(() => validateShapeSpec({ kind: 'compound', parts: [{ shape: GOOD[7]! }] })).toThrow(/not compound/);
    expect(() => validateShapeSpec({ kind: 'compound', parts: [] })).toThrow(/at least one part/);
  });
});

describe('checkVec3 / checkQuat', () => {
  it('accept finite vectors and unit quaternions and refuse the rest', () => {
    expect(() => checkVec3({ x: 1, y: 2, z: 3 }, 'body', 'position')).not.toThrow();
    expect(() => checkVec3(null, 'body', 'position')).toThrow(/^body: position must be an \{x, y, z\} object$/);
    expect(() => checkVec3({ x: 1, y: Number.POSITIVE_INFINITY, z: 3 }, 'body', 'position')).toThrow(/position\.y must be a finite number/);
    expect(() => checkQuat({ x: 0, y: 0, z: 0, w: 1 }, 'body', 'rotation')).not.toThrow();
    expect(() => checkQuat({ x: 0, y: 0, z: 0, w: 2 }, 'body', 'rotation')).toThrow(/rotation must be a unit quaternion/);
  });
});
