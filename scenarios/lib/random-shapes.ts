// Seeded random geometry for scenarios: unit quaternions, convex-hull point clouds and mixed primitive shapes.
// Every draw comes from the caller's Prng and uses arithmetic and Math.sqrt only (identical in every JS engine).
import type { QuatLike, ShapeSpec, Vec3Like } from '../../shared/physics/index.ts';
import type { Prng } from '../../shared/sim/prng.ts';

/** A uniformly distributed unit quaternion (rejection sampling in the 4-ball). */
export function randomUnitQuat(rng: Prng): QuatLike {
  for (;;) {
    const x = rng.range(-1, 1);
    const y = rng.range(-1, 1);
    const z = rng.range(-1, 1);
    const w = rng.range(-1, 1);
    const lenSq = x * x + y * y + z * z + w * w;
    if (lenSq > 0.01 && lenSq <= 1) {
      const inv = 1 / Math.sqrt(lenSq);
      return { x: x * inv, y: y * inv, z: z * inv, w: w * inv };
    }
  }
}

/** A uniformly distributed unit vector (rejection sampling in the 3-ball). */
export function randomUnitVector(rng: Prng): Vec3Like {
  for (;;) {
    const x = rng.range(-1, 1);
    const y = rng.range(-1, 1);
    const z = rng.range(-1, 1);
    const lenSq = x * x + y * y + z * z;
    if (lenSq > 0.01 && lenSq <= 1) {
      const inv = 1 / Math.sqrt(lenSq);
      return { x: x * inv, y: y * inv, z: z * inv };
    }
  }
}

/**
 * A point cloud for a convex hull: `pointCount` points (>= 4) on an ellipsoid with the given radii (m). The first
 * four form a tetrahedron, so the hull always has volume whatever the rest of the draw.
 */
export function randomHullPoints(rng: Prng, radii: Vec3Like, pointCount: number): number[] {
  if (!Number.isInteger(pointCount) || pointCount < 4) throw new Error(`randomHullPoints: pointCount must be an integer >= 4, got ${pointCount}`);
  const out: number[] = [];
  const tetra = [
    [1, 1, 1],
    [1, -1, -1],
    [-1, 1, -1],
    [-1, -1, 1],
  ];
  const k = 0.5773502691896258; // 1/√3: tetrahedron corners on the unit sphere
  for (const [x, y, z] of tetra) out.push(x * k * radii.x, y * k * radii.y, z * k * radii.z);
  for (let i = 4; i < pointCount; i++) {
    const d = randomUnitVector(rng);
    out.push(d.x * radii.x, d.y * radii.y, d.z * radii.z);
  }
  return out;
}

/** The kinds of dynamic primitive randomMixedShape picks from. */
export const MIXED_SHAPE_KINDS = ['box', 'sphere', 'capsule', 'convexHull'] as const;

/** A random box, sphere, capsule or convex hull whose size is about `sizeMetres` (largest extent ≈ 2·size). */
export function randomMixedShape(rng: Prng, sizeMetres: number): ShapeSpec {
  const kind = rng.pick(MIXED_SHAPE_KINDS);
  const s = (lo: number, hi: number): number => sizeMetres * rng.range(lo, hi);
  switch (kind) {
    case 'box':
      return { kind: 'box', halfExtents: { x: s(0.5, 1), y: s(0.5, 1), z: s(0.5, 1) } };
    case 'sphere':
      return { kind: 'sphere', radius: s(0.6, 1) };
    case 'capsule':
      return { kind: 'capsule', halfHeight: s(0.4, 0.8), radius: s(0.35, 0.55) };
    case 'convexHull':
      return { kind: 'convexHull', points: randomHullPoints(rng, { x: s(0.6, 1), y: s(0.6, 1), z: s(0.6, 1) }, rng.int(8, 16)) };
  }
}
