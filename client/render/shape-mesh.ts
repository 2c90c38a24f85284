// ShapeSpec → renderable mesh: which cached mesh a shape uses (its key), the per-instance scale, and how to build it.
// Boxes, spheres and cylinders share one unit mesh scaled per instance; other kinds get a mesh per distinct shape.
import { validateShapeSpec, type CompoundPart, type ShapeSpec } from '../../shared/physics-data/shape-spec.ts';
import type { Vec3 } from './mat4.ts';
import { MeshBuilder, type MeshData } from './mesh-data.ts';
import { unitBoxMesh, unitCapsuleMesh, unitCylinderMesh, unitSphereMesh } from './primitive-meshes.ts';
import { quickHull } from './quickhull.ts';

/** Height fields are drawn with at most this many samples per side (larger ones are subsampled). */
export const MAX_RENDER_HEIGHTFIELD_SAMPLES = 257;

/** Which mesh a shape draws with, the scale applied per instance, and a builder for the mesh (run once per key). */
export interface ShapeMeshRef {
  key: string;
  scale: Vec3;
  build: () => MeshData;
}

type HeightFieldSpec = Extract<ShapeSpec, { kind: 'heightField' }>;

/** Resolves a shape description to its mesh; throws a clear Error for an invalid description. */
export function shapeMeshRef(spec: ShapeSpec, what = 'shape'): ShapeMeshRef {
  validateShapeSpec(spec, what);
  switch (spec.kind) {
    case 'box':
      return { key: 'box', scale: [spec.halfExtents.x, spec.halfExtents.y, spec.halfExtents.z], build: unitBoxMesh };
    case 'sphere':
      return { key: 'sphere', scale: [spec.radius, spec.radius, spec.radius], build: () => unitSphereMesh() };
    case 'cylinder':
      return { key: 'cylinder', scale: [spec.radius, spec.halfHeight, spec.radius], build: () => unitCylinderMesh() };
    case 'capsule': {
      // Round the ratio (to 1/50: under 1 % of the radius off) so capsules of similar proportions share one mesh.
      const ratio = Math.max(0.02, Math.round((spec.halfHeight / spec.radius) * 50) / 50);
      return { key: `capsule:${ratio}`, scale: [spec.radius, spec.radius, spec.radius], build: () => unitCapsuleMesh(ratio) };
    }
    case 'convexHull':
      return { key: `hull:${hashNumbers(spec.points)}`, scale: [1, 1, 1], build: () => convexHullMesh(spec.points, what) };
    case 'mesh':
      return {
        key: `mesh:${hashNumbers(spec.positions)}:${hashNumbers(spec.indices)}`,
        scale: [1, 1, 1],
        build: () => triangleMeshMesh(spec.positions, spec.indices, what),
      };
    case 'heightField': {
      const o = spec.originXz ?? { x: 0, z: 0 };
      const key = `heightField:${spec.sampleCount}:${spec.cellSize}:${o.x}:${o.z}:${hashNumbers(spec.heights)}`;
      return { key, scale: [1, 1, 1], build: () => heightFieldMesh(spec, what) };
    }
    case 'compound':
      return { key: `compound:${compoundHash(spec.parts)}`, scale: [1, 1, 1], build: () => compoundMesh(spec.parts, what) };
  }
}

/** A flat-shaded mesh of the convex hull of x,y,z triples. */
export function convexHullMesh(points: ArrayLike<number>, what = 'convex hull'): MeshData {
  let triangles: Uint32Array;
  try {
    triangles = quickHull(points);
  } catch (err) {
    throw new Error(`${what}: ${(err as Error).message}`);
  }
  const m = new MeshBuilder();
  for (let t = 0; t < triangles.length; t += 3) m.flatTriangle(points, triangles[t], triangles[t + 1], triangles[t + 2]);
  return m.build(what);
}

/** A triangle mesh drawn from both sides (its winding is the author's choice), flat-shaded. */
export function triangleMeshMesh(positions: ArrayLike<number>, indices: ArrayLike<number>, what = 'mesh'): MeshData {
  const m = new MeshBuilder();
  for (let t = 0; t < indices.length; t += 3) {
    m.flatTriangle(positions, indices[t], indices[t + 1], indices[t + 2]);
    m.flatTriangle(positions, indices[t], indices[t + 2], indices[t + 1]);
  }
  return m.build(what);
}

/** A height field as a smooth, upward-facing grid (sample (x, z) at heights[z·n + x], like Jolt's layout). */
export function heightFieldMesh(spec: HeightFieldSpec, what = 'height field'): MeshData {
  const n = spec.sampleCount;
  const cell = spec.cellSize;
  const o = spec.originXz ?? { x: 0, z: 0 };
  const h = (x: number, z: number): number => spec.heights[Math.min(n - 1, Math.max(0, z)) * n + Math.min(n - 1, Math.max(0, x))];
  const stride = Math.max(1, Math.ceil((n - 1) / (MAX_RENDER_HEIGHTFIELD_SAMPLES - 1)));
  const coords: number[] = [];
  for (let i = 0; i < n - 1; i += stride) coords.push(i);
  coords.push(n - 1);
  const m = new MeshBuilder();
  for (const z of coords) {
    for (const x of coords) {
      // Central differences on the full-resolution grid.
      const dx = (h(x + 1, z) - h(x - 1, z)) / ((Math.min(n - 1, x + 1) - Math.max(0, x - 1)) * cell);
      const dz = (h(x, z + 1) - h(x, z - 1)) / ((Math.min(n - 1, z + 1) - Math.max(0, z - 1)) * cell);
      const len = Math.sqrt(dx * dx + 1 + dz * dz);
      m.vertex(o.x + x * cell, h(x, z), o.z + z * cell, -dx / len, 1 / len, -dz / len);
    }
  }
  const side = coords.length;
  for (let zi = 0; zi < side - 1; zi++) {
    for (let xi = 0; xi < side - 1; xi++) {
      const a = zi * side + xi;
      const b = a + 1;
      const c = a + side;
      const d = c + 1;
      // Counter-clockwise seen from above (+Y): x right, z toward the viewer.
      m.triangle(a, c, b);
      m.triangle(b, c, d);
    }
  }
  return m.build(what);
}

/** Scales a unit mesh non-uniformly (normals corrected with the inverse scale). */
export function scaleMesh(mesh: MeshData, scale: Vec3): MeshData {
  const positions = new Float32Array(mesh.positions.length);
  const normals = new Float32Array(mesh.normals.length);
  for (let i = 0; i < positions.length; i += 3) {
    positions[i] = mesh.positions[i] * scale[0];
    positions[i + 1] = mesh.positions[i + 1] * scale[1];
    positions[i + 2] = mesh.positions[i + 2] * scale[2];
    const nx = mesh.normals[i] / scale[0];
    const ny = mesh.normals[i + 1] / scale[1];
    const nz = mesh.normals[i + 2] / scale[2];
    const len = Math.sqrt(nx * nx + ny * ny + nz * nz) || 1;
    normals[i] = nx / len;
    normals[i + 1] = ny / len;
    normals[i + 2] = nz / len;
  }
  return { positions, normals, indices: mesh.indices };
}

/** One merged mesh of a compound's parts, each placed at its position and rotation. */
export function compoundMesh(parts: readonly CompoundPart[], what = 'compound'): MeshData {
  const m = new MeshBuilder();
  parts.forEach((part, i) => {
    const ref = shapeMeshRef(part.shape, `${what} part ${i}`);
    const mesh = scaleMesh(ref.build(), ref.scale);
    const t = part.position ?? { x: 0, y: 0, z: 0 };
    const q = part.rotation ?? { x: 0, y: 0, z: 0, w: 1 };
    m.append(mesh, [t.x, t.y, t.z], [q.x, q.y, q.z, q.w]);
  });
  return m.build(what);
}

/** A 64-bit FNV-1a style hash (two 32-bit lanes) of a number array's exact float64 bits, as 16 hex chars. */
export function hashNumbers(values: ArrayLike<number>): string {
  const f = new Float64Array(1);
  const u = new Uint32Array(f.buffer);
  let h1 = 0x811c9dc5;
  let h2 = 0x01000193 ^ values.length;
  for (let i = 0; i < values.length; i++) {
    f[0] = values[i];
    h1 = Math.imul(h1 ^ u[0], 0x01000193) >>> 0;
    h1 = Math.imul(h1 ^ u[1], 0x01000193) >>> 0;
    h2 = Math.imul(h2 ^ u[1], 0x5bd1e995) >>> 0;
    h2 = Math.imul(h2 ^ u[0], 0x5bd1e995) >>> 0;
  }
  return h1.toString(16).padStart(8, '0') + h2.toString(16).padStart(8, '0');
}

function compoundHash(parts: readonly CompoundPart[]): string {
  const flat: number[] = [parts.length];
  for (const part of parts) {
    const s = part.shape;
    flat.push(['box', 'sphere', 'capsule', 'cylinder', 'convexHull'].indexOf(s.kind));
    if (s.kind === 'box') flat.push(s.halfExtents.x, s.halfExtents.y, s.halfExtents.z);
    else if (s.kind === 'sphere') flat.push(s.radius);
    else if (s.kind === 'capsule' || s.kind === 'cylinder') flat.push(s.halfHeight, s.radius);
    else if (s.kind === 'convexHull') flat.push(s.points.length, ...Array.from(s.points));
    const t = part.position ?? { x: 0, y: 0, z: 0 };
    const q = part.rotation ?? { x: 0, y: 0, z: 0, w: 1 };
    flat.push(t.x, t.y, t.z, q.x, q.y, q.z, q.w);
  }
  return hashNumbers(flat);
}
