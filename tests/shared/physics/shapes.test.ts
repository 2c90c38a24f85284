// Tests of shape building: every kind of bad input throws a clear Error and leaks nothing (not one heap byte),
// height fields of any size hold their samples to the millimetre, and compounds keep their parts alive.
import { describe, expect, it } from 'vitest';
import { buildShape, validateShapeSpec, type BodyOptions, type ShapeSpec } from '../../../shared/physics/index.ts';
import { makeWorld, run } from '../../helpers/physics.ts';

const ORIGIN = { x: 0, y: 0, z: 0 };
const TETRA = [0, 0, 0, 1, 0, 0, 0, 1, 0, 0, 0, 1];

/** Bad inputs and the message each must produce. */
const BAD_SHAPES: Array<[string, ShapeSpec, RegExp]> = [
  ['an empty hull', { kind: 'convexHull', points: [] }, /needs at least 4 points, got 0/],
  ['a hull of 3 points', { kind: 'convexHull', points: [0, 0, 0, 1, 0, 0, 0, 1, 0] }, /at least 4 points/],
  ['a hull with a dangling coordinate', { kind: 'convexHull', points: [...TETRA, 1] }, /not a multiple of 3/],
  ['a coplanar hull', { kind: 'convexHull', points: [0, 0, 0, 1, 0, 0, 0, 0, 1, 1, 0, 1, 0.5, 0, 0.5] }, /coplanar|area was too small/],
  ['a hull of one repeated point', { kind: 'convexHull', points: [1, 2, 3, 1, 2, 3, 1, 2, 3, 1, 2, 3] }, /Jolt could not build the shape/],
  ['a collinear hull', { kind: 'convexHull', points: [0, 0, 0, 1, 1, 1, 2, 2, 2, 3, 3, 3] }, /Jolt could not build the shape|coplanar/],
  ['a hull point that is NaN', { kind: 'convexHull', points: [0, 0, 0, 1, 0, 0, 0, 1, 0, 0, 0, Number.NaN] }, /points\[11\] must be a finite number, got NaN/],
  ['a degenerate triangle', { kind: 'mesh', positions: [0, 0, 0, 1, 0, 0, 2, 0, 0], indices: [0, 1, 2] }, /triangle 0 is degenerate/],
  ['a triangle using one vertex twice', { kind: 'mesh', positions: TETRA, indices: [0, 2, 1, 0, 1, 1] }, /triangle 1 is degenerate/],
  ['an index out of range', { kind: 'mesh', positions: TETRA, indices: [0, 2, 4] }, /indices\[2\] = 4 is out of range \(vertex count 4\)/],
  ['a negative index', { kind: 'mesh', positions: TETRA, indices: [0, -1, 2] }, /indices\[1\] = -1 is out of range/],
  ['a fractional index', { kind: 'mesh', positions: TETRA, indices: [0, 1.5, 2] }, /indices\[1\] = 1.5/],
  ['a partial triangle', { kind: 'mesh', positions: TETRA, indices: [0, 1] }, /whole triangles/],
  ['a mesh without vertices', { kind: 'mesh', positions: [], indices: [0, 1, 2] }, /positions must hold x,y,z triples/],
  ['an infinite vertex', { kind: 'mesh', positions: [0, 0, 0, 1, 0, Number.POSITIVE_INFINITY, 0, 0, 1], indices: [0, 2, 1] }, /positions\[5\] must be a finite number, got Infinity/],
  ['a zero-size box', { kind: 'box', halfExtents: { x: 1, y: 0, z: 1 } }, /halfExtents.y must be > 0, got 0/],
  ['a NaN box', { kind: 'box', halfExtents: { x: Number.NaN, y: 1, z: 1 } }, /halfExtents.x must be a finite number, got NaN/],
  ['a negative sphere', { kind: 'sphere', radius: -1 }, /radius must be > 0, got -1/],
  ['an infinite sphere', { kind: 'sphere', radius: Number.POSITIVE_INFINITY }, /radius must be a finite number/],
  ['a flat capsule', { kind: 'capsule', halfHeight: 0, radius: 0.3 }, /halfHeight must be > 0/],
  ['a thin cylinder', { kind: 'cylinder', halfHeight: 1, radius: -0.1 }, /radius must be > 0/],
  ['a height field with too few samples', { kind: 'heightField', heights: [0, 0, 0, 0, 0, 0, 0, 0], sampleCount: 3, cellSize: 1 }, /must hold sampleCount² = 9 samples, got 8/],
  ['a height field of one sample', { kind: 'heightField', heights: [0], sampleCount: 1, cellSize: 1 }, /sampleCount must be an integer in \[2, 4096\], got 1/],
  ['a height field with a fractional size', { kind: 'heightField', heights: [0, 0, 0, 0], sampleCount: 2.5, cellSize: 1 }, /sampleCount must be an integer/],
  ['a height field with a NaN sample', { kind: 'heightField', heights: [0, 0, Number.NaN, 0], sampleCount: 2, cellSize: 1 }, /heights\[2\] must be a finite number, got NaN/],
  ['a height field with no cell size', { kind: 'heightField', heights: [0, 0, 0, 0], sampleCount: 2, cellSize: 0 }, /cellSize must be > 0/],
  ['a height field with a NaN origin', { kind: 'heightField', heights: [0, 0, 0, 0], sampleCount: 2, cellSize: 1, originXz: { x: Number.NaN, z: 0 } }, /originXz.x/],
  ['an empty compound', { kind: 'compound', parts: [] }, /needs at least one part/],
  ['a compound holding a mesh', { kind: 'compound', parts: [{ shape: { kind: 'mesh', positions: TETRA, indices: [0, 2, 1] } }] }, /part 0: a compound part must be a convex shape, not mesh/],
  ['a compound with a bad part', { kind: 'compound', parts: [{ shape: { kind: 'sphere', radius: 1 } }, { shape: { kind: 'box', halfExtents: { x: 1, y: 1, z: -1 } } }] }, /part 1: halfExtents.z must be > 0/],
  ['a compound with a flat hull part', { kind: 'compound', parts: [{ shape: { kind: 'sphere', radius: 1 } }, { shape: { kind: 'convexHull', points: [0, 0, 0, 1, 0, 0, 0, 0, 1, 1, 0, 1] } }] }, /part 1.*(coplanar|area was too small)/],
  ['a compound part at NaN', { kind: 'compound', parts: [{ shape: { kind: 'sphere', radius: 1 }, position: { x: 0, y: Number.NaN, z: 0 } }] }, /part 0: position.y/],
  ['an unknown kind', { kind: 'torus' } as unknown as ShapeSpec, /unknown shape kind "torus"/],
];

/** Bad body options and placements for a good shape, with their messages. */
const BAD_BODIES: Array<[string, BodyOptions, RegExp, { pos?: unknown; rot?: unknown }?]> = [
  ['a NaN position', {}, /position.x must be a finite number, got NaN/, { pos: { x: Number.NaN, y: 0, z: 0 } }],
  ['an infinite position', {}, /position.z must be a finite number, got -Infinity/, { pos: { x: 0, y: 0, z: Number.NEGATIVE_INFINITY } }],
  ['a non-unit rotation', {}, /rotation must be a unit quaternion/, { rot: { x: 0, y: 0, z: 0, w: 2 } }],
  ['a NaN rotation', {}, /rotation.w must be a finite number/, { rot: { x: 0, y: 0, z: 0, w: Number.NaN } }],
  ['a NaN restitution', { restitution: Number.NaN }, /restitution must be a finite number in \[0, 1\], got NaN/],
  ['a restitution above 1', { restitution: 1.5 }, /restitution must be a finite number in \[0, 1\]/],
  ['an infinite friction', { friction: Number.POSITIVE_INFINITY }, /friction must be a finite number/],
  ['a negative damping', { linearDamping: -1 }, /linearDamping/],
  ['a NaN mass', { massKg: Number.NaN }, /massKg must be a finite number > 0, got NaN/],
  ['a zero mass', { massKg: 0 }, /massKg must be a finite number > 0, got 0/],
  ['a NaN velocity', { linearVelocity: { x: 0, y: Number.NaN, z: 0 } }, /linearVelocity.y must be a finite number/],
  ['an infinite spin', { angularVelocity: { x: Number.POSITIVE_INFINITY, y: 0, z: 0 } }, /angularVelocity.x/],
  ['an unknown motion', { motion: 'floating' as never }, /motion must be 'static', 'dynamic' or 'kinematic'/],
  ['an unknown motion quality', { motionQuality: 'perfect' as never }, /motionQuality must be 'discrete' or 'linearCast'/],
  ['a bad no-collide group', { noCollideGroup: -2 }, /noCollideGroup must be an integer/],
];

describe('shapes', () => {
  it('refuses every bad shape with a clear Error, leaking not one heap byte and creating no body', async () => {
    const w = await makeWorld();
    const attempt = (): void => {
      for (const [, spec, message] of BAD_SHAPES) expect(() => w.addShape(spec, ORIGIN, null, { motion: 'static' })).toThrow(message);
    };
    attempt(); // warm-up: the allocator keeps some freed blocks cached
    const before = w.freeHeapBytes();
    for (let i = 0; i < 20; i++) attempt();
    expect(w.freeHeapBytes()).toBe(before);
    expect(w.bodyCount).toBe(0);
    w.addBox({ x: 5, y: 0.5, z: 5 }, { x: 0, y: -0.5, z: 0 }, null, { motion: 'static' });
    const ball = w.addSphere(0.5, { x: 0, y: 3, z: 0 });
    run(w, 120);
    expect(ball.position().y).toBeCloseTo(0.5, 2); // the world still works
    w.destroy();
  });

  it('names the shape and the body in each message', async () => {
    const w = await makeWorld();
    expect(() => w.addBox({ x: 1, y: 0, z: 1 }, ORIGIN, null, { name: 'crate 7' })).toThrow(/^box "crate 7": halfExtents.y must be > 0/);
    expect(() => w.addConvexHull([], ORIGIN)).toThrow(/^convexHull: /);
    w.destroy();
  });

  it('refuses bad placements and options for a good shape, leaking nothing', async () => {
    const w = await makeWorld();
    const attempt = (): void => {
      for (const [, opts, message, place] of BAD_BODIES) {
        const pos = (place?.pos ?? ORIGIN) as { x: number; y: number; z: number };
        const rot = (place?.rot ?? null) as null;
        expect(() => w.addConvexHull(TETRA, pos, rot, opts)).toThrow(message);
      }
    };
    attempt();
    const before = w.freeHeapBytes();
    for (let i = 0; i < 20; i++) attempt();
    expect(w.freeHeapBytes()).toBe(before);
    expect(w.bodyCount).toBe(0);
    w.destroy();
  });

  it('validates descriptions on their own, before any Jolt object exists', () => {
    for (const [, spec, message] of BAD_SHAPES.filter(([name]) => !/one repeated point|collinear|coplanar|flat hull/.test(name))) {
      expect(() => validateShapeSpec(spec)).toThrow(message);
    }
    expect(() => validateShapeSpec({ kind: 'sphere', radius: 1 })).not.toThrow();
    expect(() => validateShapeSpec(null as unknown as ShapeSpec)).toThrow(/must be an object/);
  });

  it('builds a standalone shape holding exactly one reference for the caller', async () => {
    const w = await makeWorld();
    const spec: ShapeSpec = { kind: 'compound', parts: [{ shape: { kind: 'sphere', radius: 0.5 } }, { shape: { kind: 'convexHull', points: TETRA }, position: { x: 1, y: 0, z: 0 } }] };
    buildShape(w.jolt, spec).Release(); // warm-up
    const before = w.freeHeapBytes();
    for (let i = 0; i < 200; i++) {
      const shape = buildShape(w.jolt, spec);
      expect(shape.GetRefCount()).toBe(1);
      shape.Release();
    }
    expect(w.freeHeapBytes()).toBe(before);
    w.destroy();
  });

  it('builds height fields of any size from 2×2 up, holding every sample within a millimetre', async () => {
    const w = await makeWorld();
    for (const n of [2, 3, 4, 5, 8, 9, 33]) {
      const heights: number[] = [];
      for (let z = 0; z < n; z++) for (let x = 0; x < n; x++) heights.push(((x * 5 + z * 3) % 7) * 1.3 - 2 + (x === 1 && z === 1 ? 6 : 0));
      const ox = n * 100;
      w.addHeightField(heights, n, 1, { x: ox, z: 0 });
      for (let z = 0; z < n; z++) {
        for (let x = 0; x < n; x++) {
          // Sample points on the outer edge are probed a hair inside the field.
          const px = ox + Math.min(Math.max(x, 0.001), n - 1.001);
          const pz = Math.min(Math.max(z, 0.001), n - 1.001);
          const y = w.rayDownY(px, 50, pz, 100);
          expect(y, `n=${n} sample (${x}, ${z})`).not.toBeNull();
          expect(Math.abs(y! - heights[z * n + x]), `n=${n} sample (${x}, ${z})`).toBeLessThan(0.02);
        }
      }
      // Interior samples exactly (no edge clamping): the stored precision is 1 mm.
      if (n >= 3) expect(Math.abs(w.rayDownY(ox + 1, 50, 1, 100)! - heights[n + 1])).toBeLessThan(0.0015);
      expect(w.rayDownY(ox + n - 1 + 0.3, 50, 0.5, 100)).toBeNull(); // nothing past the last sample
      expect(w.rayDownY(ox + 0.5, 50, n - 1 + 0.3, 100)).toBeNull();
    }
    w.destroy();
  });

  it('keeps a compound\'s parts alive for as long as its body lives', async () => {
    const w = await makeWorld();
    w.addBox({ x: 5, y: 0.5, z: 5 }, { x: 0, y: -0.5, z: 0 }, null, { motion: 'static' });
    const parts = [
      { shape: { kind: 'convexHull' as const, points: TETRA }, position: { x: -0.6, y: 0, z: 0 } },
      { shape: { kind: 'capsule' as const, halfHeight: 0.3, radius: 0.2 }, position: { x: 0.6, y: 0, z: 0 }, rotation: { x: 0, y: 0, z: 0.7071068, w: 0.7071068 } },
    ];
    const body = w.addCompound(parts, { x: 0, y: 2, z: 0 });
    run(w, 200); // the parts are used by every contact: freed parts would corrupt the heap or crash here
    expect(body.position().y).toBeGreaterThan(0);
    expect(body.position().y).toBeLessThan(1);
    w.removeBody(body);
    run(w, 5);
    w.destroy();
  });
});
