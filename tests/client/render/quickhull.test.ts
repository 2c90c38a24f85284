// Tests of the deterministic quickhull: closed, outward-facing hulls that contain every input point.
import { describe, expect, it } from 'vitest';
import { quickHull } from '../../../client/render/quickhull.ts';

function lcg(seed: number): () => number {
  let s = seed >>> 0;
  return () => {
    s = (Math.imul(s, 1664525) + 1013904223) >>> 0;
    return s / 4294967296;
  };
}

function normal(p: ArrayLike<number>, a: number, b: number, c: number): [number, number, number] {
  const u = [p[b * 3] - p[a * 3], p[b * 3 + 1] - p[a * 3 + 1], p[b * 3 + 2] - p[a * 3 + 2]];
  const v = [p[c * 3] - p[a * 3], p[c * 3 + 1] - p[a * 3 + 1], p[c * 3 + 2] - p[a * 3 + 2]];
  const n: [number, number, number] = [u[1] * v[2] - u[2] * v[1], u[2] * v[0] - u[0] * v[2], u[0] * v[1] - u[1] * v[0]];
  const len = Math.hypot(...n);
  return [n[0] / len, n[1] / len, n[2] / len];
}

/** Checks closedness (every directed edge has its reverse once), and that no point lies outside any face. */
function checkHull(points: number[], tris: Uint32Array): void {
  const edges = new Map<string, number>();
  for (let t = 0; t < tris.length; t += 3) {
    for (const [u, v] of [[tris[t], tris[t + 1]], [tris[t + 1], tris[t + 2]], [tris[t + 2], tris[t]]]) {
      const key = `${u},${v}`;
      if (edges.has(key)) throw new Error(`directed edge ${key} appears twice`);
      edges.set(key, t);
    }
  }
  const open = [...edges.keys()].filter((key) => {
    const [u, v] = key.split(',');
    return !edges.has(`${v},${u}`);
  });
  expect(open, 'edges without a twin: the hull is open').toEqual([]);
  const scale = Math.max(...points.map(Math.abs));
  let worst = -Infinity;
  for (let t = 0; t < tris.length; t += 3) {
    const n = normal(points, tris[t], tris[t + 1], tris[t + 2]);
    const a = tris[t] * 3;
    for (let i = 0; i < points.length / 3; i++) {
      const d = n[0] * (points[i * 3] - points[a]) + n[1] * (points[i * 3 + 1] - points[a + 1]) + n[2] * (points[i * 3 + 2] - points[a + 2]);
      worst = Math.max(worst, d);
    }
  }
  expect(worst, 'a point lies outside a hull face').toBeLessThanOrEqual(scale * 1e-5);
}

describe('quickHull', () => {
  it('triangulates a cube into 12 outward triangles using only its corners', () => {
    const pts: number[] = [];
    for (const x of [-1, 1]) for (const y of [-1, 1]) for (const z of [-1, 1]) pts.push(x, y, z);
    pts.push(0, 0, 0, 0.5, 0.2, -0.3); // interior points must not appear
    const tris = quickHull(pts);
    expect(tris.length / 3).toBe(12);
    expect(new Set(tris).size).toBe(8);
    expect([...tris].every((i) => i < 8)).toBe(true);
    checkHull(pts, tris);
  });

  it('builds a closed hull of a random cloud that contains every point (Euler V − E + F = 2)', () => {
    const rand = lcg(42);
    const pts: number[] = [];
    for (let i = 0; i < 600; i++) pts.push(rand() * 2 - 1, rand() * 3 - 1.5, rand() - 0.5);
    const tris = quickHull(pts);
    checkHull(pts, tris);
    const v = new Set(tris).size;
    const f = tris.length / 3;
    const e = (f * 3) / 2;
    expect(v - e + f).toBe(2);
  });

  it('handles points on a sphere, duplicates and coplanar faces', () => {
    const rand = lcg(9);
    const pts: number[] = [];
    for (let i = 0; i < 200; i++) {
      const u = rand() * 2 - 1;
      const a = rand() * Math.PI * 2;
      const r = Math.sqrt(1 - u * u);
      pts.push(r * Math.cos(a), u, r * Math.sin(a));
    }
    pts.push(...pts.slice(0, 30)); // ten duplicated points
    for (let i = 0; i < 20; i++) pts.push(-1, rand() - 0.5, rand() - 0.5); // a flat face at x = −1
    checkHull(pts, quickHull(pts));
  });

  it('gives the same triangles in the same order for the same input', () => {
    const rand = lcg(5);
    const pts = Array.from({ length: 300 }, () => rand() * 4 - 2);
    expect(Array.from(quickHull(pts))).toEqual(Array.from(quickHull(pts.slice())));
  });

  it('rejects clouds without volume and malformed input with clear errors', () => {
    expect(() => quickHull([0, 0, 0, 1, 0, 0, 0, 1, 0])).toThrow(/at least 4 points/);
    expect(() => quickHull([0, 0, 0, 1, 0, 0, 0, 1, 0, 1, 1, 0, 2, 3, 0])).toThrow(/coplanar/);
    expect(() => quickHull([0, 0, 0, 1, 1, 1, 2, 2, 2, 3, 3, 3])).toThrow(/collinear/);
    expect(() => quickHull([1, 1, 1, 1, 1, 1, 1, 1, 1, 1, 1, 1])).toThrow(/coincide/);
    expect(() => quickHull([0, 0, 0, 1, 0, 0, 0, 1, 0, 0, 0, Number.NaN])).toThrow(/points\[11\] must be a finite number/);
    expect(() => quickHull([0, 0, 0, 1, 0, 0, 0, 1, 0, 0, 0, 1, 5])).toThrow(/multiple of 3/);
  });
});
