// Tests for scenarios/lib/random-shapes.ts: unit quaternions and vectors, hull clouds that always have volume, the
// mix of primitive kinds, and determinism from the Prng.
import { describe, expect, it } from 'vitest';
import { randomHullPoints, randomMixedShape, randomUnitQuat, randomUnitVector } from '../../../scenarios/lib/random-shapes.ts';
import { Prng } from '../../../shared/sim/prng.ts';

describe('random-shapes', () => {
  it('draws unit quaternions and vectors covering every sign', () => {
    const rng = new Prng(3);
    const signs = new Set<string>();
    for (let i = 0; i < 200; i++) {
      const q = randomUnitQuat(rng);
      expect(q.x * q.x + q.y * q.y + q.z * q.z + q.w * q.w).toBeCloseTo(1, 12);
      const v = randomUnitVector(rng);
      expect(v.x * v.x + v.y * v.y + v.z * v.z).toBeCloseTo(1, 12);
      signs.add([q.x, q.y, q.z, q.w].map((c) => (c < 0 ? '-' : '+')).join(''));
    }
    expect(signs.size).toBe(16);
  });

  it('builds hull clouds of the asked size, on the ellipsoid, around a volume-giving tetrahedron', () => {
    const rng = new Prng(4);
    const radii = { x: 1, y: 0.5, z: 2 };
    const pts = randomHullPoints(rng, radii, 10);
    expect(pts).toHaveLength(30);
    for (let i = 0; i < pts.length; i += 3) {
      const e = (pts[i] / radii.x) ** 2 + (pts[i + 1] / radii.y) ** 2 + (pts[i + 2] / radii.z) ** 2;
      expect(e).toBeCloseTo(1, 9);
    }
    // The first four points span a tetrahedron with positive volume.
    const p = (k: number) => pts.slice(3 * k, 3 * k + 3);
    const [a, b, c, d] = [p(0), p(1), p(2), p(3)];
    const u = b.map((v, i) => v - a[i]);
    const v = c.map((x, i) => x - a[i]);
    const w = d.map((x, i) => x - a[i]);
    const volume = u[0] * (v[1] * w[2] - v[2] * w[1]) - u[1] * (v[0] * w[2] - v[2] * w[0]) + u[2] * (v[0] * w[1] - v[1] * w[0]);
    expect(Math.abs(volume)).toBeGreaterThan(0.1);
    expect(() => randomHullPoints(rng, radii, 3)).toThrow(/pointCount must be an integer >= 4/);
  });

  it('mixes boxes, spheres, capsules and hulls, the same way for the same seed', () => {
    const kinds = (seed: number) => {
      const rng = new Prng(seed);
      return Array.from({ length: 60 }, () => randomMixedShape(rng, 0.5));
    };
    const a = kinds(11);
    expect(new Set(a.map((s) => s.kind))).toEqual(new Set(['box', 'sphere', 'capsule', 'convexHull']));
    expect(kinds(11)).toEqual(a);
    expect(kinds(12)).not.toEqual(a);
  });
});
