// Tests of ShapeSpec → mesh: outward winding and normals of primitives, mesh sharing keys, height-field layout,
// double-sided triangle meshes, compounds, and clear errors for bad shapes.
import { describe, expect, it } from 'vitest';
import { meshBounds, type MeshData } from '../../../client/render/mesh-data.ts';
import { unitBoxMesh, unitCapsuleMesh, unitCylinderMesh, unitSphereMesh } from '../../../client/render/primitive-meshes.ts';
import { MAX_RENDER_HEIGHTFIELD_SAMPLES, hashNumbers, shapeMeshRef } from '../../../client/render/shape-mesh.ts';
import type { ShapeSpec } from '../../../shared/physics-data/shape-spec.ts';

/** For a convex mesh around the origin: every triangle faces away from the origin, and vertex normals agree. */
function expectOutward(mesh: MeshData): void {
  const p = mesh.positions;
  const n = mesh.normals;
  let inward = 0;
  let disagreeing = 0;
  for (let t = 0; t < mesh.indices.length; t += 3) {
    const [a, b, c] = [mesh.indices[t] * 3, mesh.indices[t + 1] * 3, mesh.indices[t + 2] * 3];
    const u = [p[b] - p[a], p[b + 1] - p[a + 1], p[b + 2] - p[a + 2]];
    const v = [p[c] - p[a], p[c + 1] - p[a + 1], p[c + 2] - p[a + 2]];
    const fn = [u[1] * v[2] - u[2] * v[1], u[2] * v[0] - u[0] * v[2], u[0] * v[1] - u[1] * v[0]];
    const centroid = [(p[a] + p[b] + p[c]) / 3, (p[a + 1] + p[b + 1] + p[c + 1]) / 3, (p[a + 2] + p[b + 2] + p[c + 2]) / 3];
    if (fn[0] * centroid[0] + fn[1] * centroid[1] + fn[2] * centroid[2] <= 0) inward++;
    for (const i of [a, b, c]) if (fn[0] * n[i] + fn[1] * n[i + 1] + fn[2] * n[i + 2] <= 0) disagreeing++;
  }
  expect(inward, 'triangles wound inward').toBe(0);
  expect(disagreeing, 'vertex normals pointing against their triangle').toBe(0);
  for (let i = 0; i < n.length; i += 3) expect(Math.hypot(n[i], n[i + 1], n[i + 2])).toBeCloseTo(1, 5);
}

describe('shape-mesh', () => {
  it('builds closed primitives wound counter-clockwise from outside with outward normals', () => {
    for (const mesh of [unitBoxMesh(), unitSphereMesh(), unitCylinderMesh(), unitCapsuleMesh(1.5)]) expectOutward(mesh);
  });

  it('sizes primitives by their spec: unit meshes with per-instance scale, capsules with round caps', () => {
    const box = shapeMeshRef({ kind: 'box', halfExtents: { x: 1, y: 2, z: 3 } });
    expect(box.key).toBe('box');
    expect(box.scale).toEqual([1, 2, 3]);
    expect(meshBounds(box.build())).toEqual([-1, -1, -1, 1, 1, 1]);
    const cyl = shapeMeshRef({ kind: 'cylinder', halfHeight: 2, radius: 0.5 });
    expect(cyl.scale).toEqual([0.5, 2, 0.5]);
    const cap = shapeMeshRef({ kind: 'capsule', halfHeight: 0.9, radius: 0.3 });
    expect(cap.scale).toEqual([0.3, 0.3, 0.3]);
    const b = meshBounds(cap.build());
    expect(b[4] * 0.3).toBeCloseTo(0.9 + 0.3, 5); // top of the cap at halfHeight + radius
    expect(b[1] * 0.3).toBeCloseTo(-1.2, 5);
    expect(b[3] * 0.3).toBeCloseTo(0.3, 2);
  });

  it('shares one mesh between same-kind primitives and capsules of the same proportions', () => {
    expect(shapeMeshRef({ kind: 'sphere', radius: 1 }).key).toBe(shapeMeshRef({ kind: 'sphere', radius: 3 }).key);
    expect(shapeMeshRef({ kind: 'capsule', halfHeight: 0.5, radius: 0.25 }).key).toBe(shapeMeshRef({ kind: 'capsule', halfHeight: 1, radius: 0.5 }).key);
    expect(shapeMeshRef({ kind: 'capsule', halfHeight: 0.5, radius: 0.25 }).key).not.toBe(shapeMeshRef({ kind: 'capsule', halfHeight: 1, radius: 0.25 }).key);
    const hullA: ShapeSpec = { kind: 'convexHull', points: [0, 0, 0, 1, 0, 0, 0, 1, 0, 0, 0, 1] };
    const hullB: ShapeSpec = { kind: 'convexHull', points: [0, 0, 0, 1, 0, 0, 0, 1, 0, 0, 0, 2] };
    expect(shapeMeshRef(hullA).key).toBe(shapeMeshRef({ ...hullA, points: Float32Array.from(hullA.points) }).key);
    expect(shapeMeshRef(hullA).key).not.toBe(shapeMeshRef(hullB).key);
  });

  it('draws a convex hull flat-shaded, outward, spanning its points', () => {
    const pts = [-1, -1, -1, 2, -1, -1, -1, 3, -1, -1, -1, 4, 0, 0, 0];
    const mesh = shapeMeshRef({ kind: 'convexHull', points: pts }).build();
    expect(mesh.indices.length).toBe(4 * 3);
    expect(meshBounds(mesh)).toEqual([-1, -1, -1, 2, 3, 4]);
    // Outward relative to an interior point.
    const shifted = { ...mesh, positions: mesh.positions.map((v, i) => v - [-0.25, 0, 0.25][i % 3]) };
    expectOutward(shifted);
  });

  it('lays a height field out like Jolt: sample (x, z) at heights[z·n + x], origin plus cell steps, normals up', () => {
    const n = 4;
    const heights = Array.from({ length: n * n }, (_, i) => i * 0.1);
    const mesh = shapeMeshRef({ kind: 'heightField', heights, sampleCount: n, cellSize: 2, originXz: { x: -3, z: 5 } }).build();
    expect(mesh.positions.length / 3).toBe(n * n);
    for (let z = 0; z < n; z++) {
      for (let x = 0; x < n; x++) {
        const v = (z * n + x) * 3;
        expect([mesh.positions[v], mesh.positions[v + 1], mesh.positions[v + 2]].map((c) => Math.round(c * 1e5) / 1e5)).toEqual([-3 + 2 * x, Math.round(heights[z * n + x] * 1e5) / 1e5, 5 + 2 * z]);
        expect(mesh.normals[v + 1]).toBeGreaterThan(0);
      }
    }
    expect(mesh.indices.length).toBe((n - 1) * (n - 1) * 6);
    // Every triangle faces up.
    for (let t = 0; t < mesh.indices.length; t += 3) {
      const [a, b, c] = [mesh.indices[t] * 3, mesh.indices[t + 1] * 3, mesh.indices[t + 2] * 3];
      const u = [mesh.positions[b] - mesh.positions[a], mesh.positions[b + 2] - mesh.positions[a + 2]];
      const w = [mesh.positions[c] - mesh.positions[a], mesh.positions[c + 2] - mesh.positions[a + 2]];
      expect(u[1] * w[0] - u[0] * w[1]).toBeGreaterThan(0); // y of (b−a) × (c−a)
    }
  });

  it('subsamples huge height fields but keeps their full extent', () => {
    const n = 1024;
    const mesh = shapeMeshRef({ kind: 'heightField', heights: new Float32Array(n * n), sampleCount: n, cellSize: 1 }).build();
    const side = Math.sqrt(mesh.positions.length / 3);
    expect(side).toBeLessThanOrEqual(MAX_RENDER_HEIGHTFIELD_SAMPLES + 1);
    expect(meshBounds(mesh)).toEqual([0, 0, 0, n - 1, 0, n - 1]);
  });

  it('draws triangle meshes from both sides', () => {
    const mesh = shapeMeshRef({ kind: 'mesh', positions: [0, 0, 0, 1, 0, 0, 0, 0, 1], indices: [0, 2, 1] }).build();
    expect(mesh.indices.length).toBe(6);
    const ys = [mesh.normals[1], mesh.normals[4], mesh.normals[7], mesh.normals[10], mesh.normals[13], mesh.normals[16]];
    expect(ys.filter((y) => y > 0.99).length).toBe(3);
    expect(ys.filter((y) => y < -0.99).length).toBe(3);
  });

  it('merges compound parts at their positions and rotations', () => {
    const spec: ShapeSpec = {
      kind: 'compound',
      parts: [
        { shape: { kind: 'box', halfExtents: { x: 0.5, y: 0.5, z: 0.5 } }, position: { x: -2, y: 0, z: 0 } },
        // A cylinder lying along X (rotated 90° about Z) at +2.
        { shape: { kind: 'cylinder', halfHeight: 1, radius: 0.25 }, position: { x: 2, y: 0, z: 0 }, rotation: { x: 0, y: 0, z: Math.SQRT1_2, w: Math.SQRT1_2 } },
      ],
    };
    const b = meshBounds(shapeMeshRef(spec).build()).map((v) => Math.round(v * 1e4) / 1e4);
    expect(b).toEqual([-2.5, -0.5, -0.5, 3, 0.5, 0.5]);
  });

  it('rejects invalid shapes with the reason, naming the body', () => {
    expect(() => shapeMeshRef({ kind: 'sphere', radius: -1 }, 'body 7')).toThrow(/body 7: radius must be > 0/);
    expect(() => shapeMeshRef({ kind: 'teapot' } as unknown as ShapeSpec)).toThrow(/unknown shape kind "teapot"/);
    expect(() => shapeMeshRef({ kind: 'convexHull', points: [0, 0, 0, 1, 0, 0, 0, 1, 0, 1, 1, 0] }, 'body 3').build()).toThrow(/body 3: convex hull: all points are coplanar/);
  });

  it('hashes number arrays by exact value', () => {
    expect(hashNumbers([1, 2, 3])).toBe(hashNumbers(Float64Array.from([1, 2, 3])));
    expect(hashNumbers([1, 2, 3])).not.toBe(hashNumbers([1, 2, 3.0000001]));
    expect(hashNumbers([1, 2])).not.toBe(hashNumbers([2, 1]));
    expect(hashNumbers([])).toMatch(/^[0-9a-f]{16}$/);
  });
});
