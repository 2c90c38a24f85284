// Shapes as plain data: the ShapeSpec union scenarios, the protocol, the renderer and the physics wrapper share, and
// its validation (sizes, finiteness, counts, index ranges, degenerate triangles). No Jolt here: shared/physics builds.
import type { QuatLike, Vec3Like } from './vectors.ts';

/** A part of a compound shape, placed relative to the compound's origin. */
export interface CompoundPart {
  shape: ShapeSpec;
  position?: Vec3Like;
  rotation?: QuatLike;
}

/** A shape as plain data: scenarios, the protocol and the renderer use the same description. */
export type ShapeSpec =
  | { kind: 'box'; halfExtents: Vec3Like }
  | { kind: 'sphere'; radius: number }
  | { kind: 'capsule'; halfHeight: number; radius: number }
  | { kind: 'cylinder'; halfHeight: number; radius: number }
  | { kind: 'convexHull'; points: ArrayLike<number> }
  | { kind: 'mesh'; positions: ArrayLike<number>; indices: ArrayLike<number> }
  | { kind: 'heightField'; heights: ArrayLike<number>; sampleCount: number; cellSize: number; originXz?: { x: number; z: number } }
  | { kind: 'compound'; parts: CompoundPart[] };

/** The kind tag of a ShapeSpec. */
export type ShapeKind = ShapeSpec['kind'];

/** Shapes that can never be dynamic (no volume/inertia). */
export const STATIC_ONLY_KINDS: ReadonlySet<ShapeKind> = new Set<ShapeKind>(['mesh', 'heightField']);

/** Largest mesh / height field we accept in one shape (keeps a single build far from the heap limit). */
export const MAX_MESH_TRIANGLES = 1_000_000;
export const MAX_HEIGHTFIELD_SAMPLES = 4096;

function fail(what: string, message: string): never {
  throw new Error(`${what}: ${message}`);
}

function checkFinite(value: number, what: string, field: string): void {
  if (typeof value !== 'number' || !Number.isFinite(value)) fail(what, `${field} must be a finite number, got ${String(value)}`);
}

function checkPositive(value: number, what: string, field: string): void {
  checkFinite(value, what, field);
  if (value <= 0) fail(what, `${field} must be > 0, got ${value}`);
}

/** Throws unless v has three finite components. */
export function checkVec3(v: Vec3Like | undefined | null, what: string, field: string): void {
  if (!v || typeof v !== 'object') fail(what, `${field} must be an {x, y, z} object`);
  checkFinite(v.x, what, `${field}.x`);
  checkFinite(v.y, what, `${field}.y`);
  checkFinite(v.z, what, `${field}.z`);
}

/** Throws unless q is a finite, (nearly) unit quaternion. */
export function checkQuat(q: QuatLike | undefined | null, what: string, field: string): void {
  if (!q || typeof q !== 'object') fail(what, `${field} must be an {x, y, z, w} object`);
  checkFinite(q.x, what, `${field}.x`);
  checkFinite(q.y, what, `${field}.y`);
  checkFinite(q.z, what, `${field}.z`);
  checkFinite(q.w, what, `${field}.w`);
  const lenSq = q.x * q.x + q.y * q.y + q.z * q.z + q.w * q.w;
  if (Math.abs(lenSq - 1) > 1e-3) fail(what, `${field} must be a unit quaternion (|q|² = ${lenSq.toFixed(6)})`);
}

function checkArray(arr: ArrayLike<number> | undefined, what: string, field: string): ArrayLike<number> {
  if (!arr || typeof arr !== 'object' || typeof arr.length !== 'number') fail(what, `${field} must be an array of numbers`);
  for (let i = 0; i < arr.length; i++) {
    const v = arr[i];
    if (typeof v !== 'number' || !Number.isFinite(v)) fail(what, `${field}[${i}] must be a finite number, got ${String(v)}`);
  }
  return arr;
}

/** Validates a shape description (sizes, finiteness, counts, index ranges, degenerate triangles). */
export function validateShapeSpec(spec: ShapeSpec, what = 'shape'): void {
  if (!spec || typeof spec !== 'object') fail(what, 'shape description must be an object');
  switch (spec.kind) {
    case 'box':
      checkVec3(spec.halfExtents, what, 'halfExtents');
      checkPositive(spec.halfExtents.x, what, 'halfExtents.x');
      checkPositive(spec.halfExtents.y, what, 'halfExtents.y');
      checkPositive(spec.halfExtents.z, what, 'halfExtents.z');
      return;
    case 'sphere':
      checkPositive(spec.radius, what, 'radius');
      return;
    case 'capsule':
    case 'cylinder':
      checkPositive(spec.halfHeight, what, 'halfHeight');
      checkPositive(spec.radius, what, 'radius');
      return;
    case 'convexHull': {
      const pts = checkArray(spec.points, what, 'points');
      if (pts.length % 3 !== 0) fail(what, `points must hold x,y,z triples (length ${pts.length} is not a multiple of 3)`);
      if (pts.length < 12) fail(what, `a convex hull needs at least 4 points, got ${pts.length / 3}`);
      return;
    }
    case 'mesh':
      validateMesh(spec.positions, spec.indices, what);
      return;
    case 'heightField': {
      const n = spec.sampleCount;
      if (!Number.isInteger(n) || n < 2 || n > MAX_HEIGHTFIELD_SAMPLES) {
        fail(what, `sampleCount must be an integer in [2, ${MAX_HEIGHTFIELD_SAMPLES}], got ${String(n)}`);
      }
      const heights = checkArray(spec.heights, what, 'heights');
      if (heights.length !== n * n) fail(what, `heights must hold sampleCount² = ${n * n} samples, got ${heights.length}`);
      checkPositive(spec.cellSize, what, 'cellSize');
      if (spec.originXz) {
        checkFinite(spec.originXz.x, what, 'originXz.x');
        checkFinite(spec.originXz.z, what, 'originXz.z');
      }
      return;
    }
    case 'compound': {
      if (!Array.isArray(spec.parts) || spec.parts.length === 0) fail(what, 'a compound needs at least one part');
      spec.parts.forEach((part, i) => {
        const partWhat = `${what} part ${i}`;
        if (!part || typeof part !== 'object') fail(partWhat, 'must be an object');
        if (part.shape?.kind === 'compound' || STATIC_ONLY_KINDS.has(part.shape?.kind)) {
          fail(partWhat, `a compound part must be a convex shape, not ${part.shape?.kind}`);
        }
        validateShapeSpec(part.shape, partWhat);
        if (part.position) checkVec3(part.position, partWhat, 'position');
        if (part.rotation) checkQuat(part.rotation, partWhat, 'rotation');
      });
      return;
    }
    default:
      fail(what, `unknown shape kind ${JSON.stringify((spec as { kind?: unknown }).kind)}`);
  }
}

function validateMesh(positionsIn: ArrayLike<number>, indicesIn: ArrayLike<number>, what: string): void {
  const positions = checkArray(positionsIn, what, 'positions');
  if (positions.length === 0 || positions.length % 3 !== 0) {
    fail(what, `positions must hold x,y,z triples (length ${positions.length})`);
  }
  const vertexCount = positions.length / 3;
  if (!indicesIn || typeof indicesIn.length !== 'number') fail(what, 'indices must be an array of integers');
  const indices = indicesIn;
  if (indices.length === 0 || indices.length % 3 !== 0) {
    fail(what, `indices must hold whole triangles (length ${indices.length} is not a positive multiple of 3)`);
  }
  if (indices.length / 3 > MAX_MESH_TRIANGLES) fail(what, `too many triangles (${indices.length / 3} > ${MAX_MESH_TRIANGLES})`);
  for (let i = 0; i < indices.length; i++) {
    const idx = indices[i];
    if (!Number.isInteger(idx) || idx < 0 || idx >= vertexCount) {
      fail(what, `indices[${i}] = ${String(idx)} is out of range (vertex count ${vertexCount})`);
    }
  }
  for (let t = 0; t < indices.length; t += 3) {
    const a = indices[t] * 3;
    const b = indices[t + 1] * 3;
    const c = indices[t + 2] * 3;
    const e1x = positions[b] - positions[a];
    const e1y = positions[b + 1] - positions[a + 1];
    const e1z = positions[b + 2] - positions[a + 2];
    const e2x = positions[c] - positions[a];
    const e2y = positions[c + 1] - positions[a + 1];
    const e2z = positions[c + 2] - positions[a + 2];
    const nx = e1y * e2z - e1z * e2y;
    const ny = e1z * e2x - e1x * e2z;
    const nz = e1x * e2y - e1y * e2x;
    if (nx * nx + ny * ny + nz * nz <= 1e-20) fail(what, `triangle ${t / 3} is degenerate (zero area)`);
  }
}
