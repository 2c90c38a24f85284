// Jolt builders for shape descriptions (the plain ShapeSpec lives in shared/physics-data/shape-spec.ts). Validates
// every input before Jolt sees it, surfaces Jolt's own build errors as Errors, and returns shapes holding exactly one
// reference: the caller's.
import { validateShapeSpec, type CompoundPart, type ShapeSpec } from '../physics-data/shape-spec.ts';
import type { JoltModule } from './jolt-backend.ts';

type J = JoltModule;
/** A built Jolt shape (ref-counted; whoever holds it Release()s it). */
export type JoltShape = InstanceType<J['Shape']>;

const DEFAULT_CONVEX_RADIUS = 0.05;
/** Smallest hull volume accepted (1 mm³): a flat hull has no mass and turns its body's state into NaN. */
const MIN_HULL_VOLUME_M3 = 1e-9;
/** Height-field samples are stored per block in as few bits as keep every sample within this error. */
const HEIGHT_FIELD_MAX_ERROR_METRES = 0.001;

/** Rough WASM heap bytes a shape's build needs (used to refuse builds that would exhaust the fixed heap). */
export function estimateShapeBytes(spec: ShapeSpec): number {
  switch (spec.kind) {
    case 'convexHull':
      return 4096 + (spec.points.length / 3) * 256;
    case 'mesh':
      // Peak while Jolt builds: measured 218-234 B per triangle (20k and 180k triangles).
      return 8192 + (spec.indices.length / 3) * 256 + (spec.positions.length / 3) * 16;
    case 'heightField':
      // Peak while Jolt builds: measured 8.3 B per sample at 8 bits; up to 16 bits per sample are used.
      return 8192 + (spec.sampleCount + 8) * (spec.sampleCount + 8) * 16;
    case 'compound':
      return 1024 + spec.parts.reduce((sum, p) => sum + estimateShapeBytes(p.shape), 0);
    default:
      return 1024;
  }
}

/**
 * Turns a settings object into a shape: takes our own reference, clears the (static, reused) ShapeResult and
 * destroys the settings. On a Jolt error, frees everything and throws with Jolt's message.
 */
function shapeFromSettings(Jm: J, settings: InstanceType<J['ShapeSettings']>, what: string): JoltShape {
  const result = settings.Create(); // a temporary in static memory: cleared, never destroyed
  if (result.HasError()) {
    const message = result.GetError().c_str();
    result.Clear();
    Jm.destroy(settings);
    throw new Error(`${what}: Jolt could not build the shape: ${message}`);
  }
  const shape = result.Get();
  shape.AddRef(); // our reference, taken before the result and the settings let go of theirs
  result.Clear();
  Jm.destroy(settings);
  return shape;
}

/** Wraps a directly constructed shape (ref count 0) with our single reference. */
function own(shape: JoltShape): JoltShape {
  shape.AddRef(); // the caller's reference; a body adds its own, then the caller Release()s this one
  return shape;
}

/** Builds a validated shape; the returned shape holds one reference owned by the caller. */
export function buildShape(Jm: J, spec: ShapeSpec, what = 'shape'): JoltShape {
  validateShapeSpec(spec, what);
  return buildValidated(Jm, spec, what);
}

/** Builds a shape validateShapeSpec already accepted (skips a second pass over big meshes). */
export function buildValidatedShape(Jm: J, spec: ShapeSpec, what = 'shape'): JoltShape {
  return buildValidated(Jm, spec, what);
}

function buildValidated(Jm: J, spec: ShapeSpec, what: string): JoltShape {
  switch (spec.kind) {
    case 'box': {
      const h = spec.halfExtents;
      const radius = Math.min(DEFAULT_CONVEX_RADIUS, Math.min(h.x, h.y, h.z) * 0.5);
      const half = new Jm.Vec3(h.x, h.y, h.z); // copied by BoxShape, freed below
      const shape = new Jm.BoxShape(half, radius); // ownership goes to the caller via own()
      Jm.destroy(half);
      return own(shape);
    }
    case 'sphere':
      return own(new Jm.SphereShape(spec.radius)); // caller owns
    case 'capsule':
      return own(new Jm.CapsuleShape(spec.halfHeight, spec.radius)); // caller owns
    case 'cylinder': {
      const radius = Math.min(DEFAULT_CONVEX_RADIUS, Math.min(spec.halfHeight, spec.radius) * 0.5);
      const settings = new Jm.CylinderShapeSettings(spec.halfHeight, spec.radius, radius); // consumed by shapeFromSettings
      return shapeFromSettings(Jm, settings, what);
    }
    case 'convexHull': {
      const settings = new Jm.ConvexHullShapeSettings(); // consumed by shapeFromSettings
      const pts = spec.points;
      const v = new Jm.Vec3(0, 0, 0); // one scratch point, copied by push_back, freed below
      settings.mPoints.reserve(pts.length / 3);
      for (let i = 0; i < pts.length; i += 3) {
        v.Set(pts[i], pts[i + 1], pts[i + 2]);
        settings.mPoints.push_back(v);
      }
      Jm.destroy(v);
      const hull = shapeFromSettings(Jm, settings, what);
      const volume = hull.GetVolume();
      if (!(volume > MIN_HULL_VOLUME_M3)) {
        hull.Release(); // our only reference: frees the shape
        throw new Error(`${what}: the points are coplanar or nearly so (hull volume ${volume} m³): a convex hull needs volume`);
      }
      return hull;
    }
    case 'mesh':
      return buildMesh(Jm, spec.positions, spec.indices, what);
    case 'heightField':
      return buildHeightField(Jm, spec, what);
    case 'compound':
      return buildCompound(Jm, spec.parts, what);
  }
}

function buildMesh(Jm: J, positions: ArrayLike<number>, indices: ArrayLike<number>, what: string): JoltShape {
  const triangles = new Jm.TriangleList(); // handed to the settings (copied), freed below
  triangles.reserve(indices.length / 3);
  const v0 = new Jm.Vec3(0, 0, 0); // three reusable corners, freed after the loop
  const v1 = new Jm.Vec3(0, 0, 0);
  const v2 = new Jm.Vec3(0, 0, 0);
  for (let t = 0; t < indices.length; t += 3) {
    const a = indices[t] * 3;
    const b = indices[t + 1] * 3;
    const c = indices[t + 2] * 3;
    v0.Set(positions[a], positions[a + 1], positions[a + 2]);
    v1.Set(positions[b], positions[b + 1], positions[b + 2]);
    v2.Set(positions[c], positions[c + 1], positions[c + 2]);
    const tri = new Jm.Triangle(v0, v1, v2); // copied into the list, freed at once
    triangles.push_back(tri);
    Jm.destroy(tri);
  }
  Jm.destroy(v0);
  Jm.destroy(v1);
  Jm.destroy(v2);
  const materials = new Jm.PhysicsMaterialList(); // copied by the settings, freed below
  const settings = new Jm.MeshShapeSettings(triangles, materials); // consumed by shapeFromSettings
  Jm.destroy(triangles);
  Jm.destroy(materials);
  return shapeFromSettings(Jm, settings, what);
}

/**
 * Jolt groups samples in blocks of blockSize² and needs at least two blocks per side; it pads a count that is not a
 * multiple with no-collision samples. Block size 4 when that leaves two blocks, else 2; a 2×2 grid is padded to 3×3.
 */
function heightFieldLayout(n: number): { blockSize: number; storedCount: number } {
  if (n >= 5) return { blockSize: 4, storedCount: n };
  return { blockSize: 2, storedCount: Math.max(n, 3) };
}

/** Fewest bits per sample (1..16) that keep every block's quantisation step within HEIGHT_FIELD_MAX_ERROR_METRES. */
function heightFieldBits(heights: ArrayLike<number>, n: number, blockSize: number): number {
  let maxRange = 0;
  for (let by = 0; by < n - 1; by += blockSize) {
    for (let bx = 0; bx < n - 1; bx += blockSize) {
      let lo = Infinity;
      let hi = -Infinity;
      for (let y = by; y <= Math.min(by + blockSize, n - 1); y++) {
        for (let x = bx; x <= Math.min(bx + blockSize, n - 1); x++) {
          const h = heights[y * n + x];
          if (h < lo) lo = h;
          if (h > hi) hi = h;
        }
      }
      if (hi - lo > maxRange) maxRange = hi - lo;
    }
  }
  let bits = 1;
  while (bits < 16 && maxRange / ((1 << bits) - 1) > HEIGHT_FIELD_MAX_ERROR_METRES) bits++;
  return bits;
}

function buildHeightField(Jm: J, spec: Extract<ShapeSpec, { kind: 'heightField' }>, what: string): JoltShape {
  const n = spec.sampleCount;
  const { blockSize, storedCount } = heightFieldLayout(n);
  const settings = new Jm.HeightFieldShapeSettings(); // consumed by shapeFromSettings
  const origin = spec.originXz ?? { x: 0, z: 0 };
  settings.mOffset.Set(origin.x, 0, origin.z);
  settings.mScale.Set(spec.cellSize, 1, spec.cellSize);
  settings.mSampleCount = storedCount;
  settings.mBlockSize = blockSize;
  settings.mBitsPerSample = heightFieldBits(spec.heights, n, blockSize);
  const samples = settings.mHeightSamples;
  samples.resize(storedCount * storedCount);
  const base = Jm.getPointer(samples.data()) >> 2;
  const heap = Jm.HEAPF32;
  const hole = Jm.HeightFieldShapeConstantValues.prototype.get_cNoCollisionValue();
  for (let y = 0; y < storedCount; y++) {
    for (let x = 0; x < storedCount; x++) heap[base + y * storedCount + x] = x < n && y < n ? spec.heights[y * n + x] : hole;
  }
  return shapeFromSettings(Jm, settings, what);
}

function buildCompound(Jm: J, parts: CompoundPart[], what: string): JoltShape {
  const built: JoltShape[] = [];
  try {
    parts.forEach((p, i) => built.push(buildValidated(Jm, p.shape, `${what} part ${i}`)));
  } catch (err) {
    for (const s of built) s.Release();
    throw err;
  }
  const settings = new Jm.StaticCompoundShapeSettings(); // consumed by shapeFromSettings
  const pos = new Jm.Vec3(0, 0, 0); // reusable, copied by AddShapeShape, freed below
  const rot = new Jm.Quat(0, 0, 0, 1); // reusable, copied by AddShapeShape, freed below
  parts.forEach((p, i) => {
    const pp = p.position ?? { x: 0, y: 0, z: 0 };
    const pr = p.rotation ?? { x: 0, y: 0, z: 0, w: 1 };
    pos.Set(pp.x, pp.y, pp.z);
    rot.Set(pr.x, pr.y, pr.z, pr.w);
    settings.AddShapeShape(pos, rot, built[i], 0); // the settings take their own reference
  });
  Jm.destroy(pos);
  Jm.destroy(rot);
  try {
    return shapeFromSettings(Jm, settings, what);
  } finally {
    for (const s of built) s.Release(); // the compound keeps the parts alive through its own references
  }
}
