// Body descriptors on the wire (welcome geometry, snapshot spawns): a table of distinct shapes plus one compact row
// per body, and the checked inverse that turns untrusted msgpack data back into BodyDescriptor[] or a clear Error.
import type { ShapeSpec } from '../physics-data/shape-spec.ts';
import { describeValue } from '../sim/describe-value.ts';
import type { BodyDescriptor } from '../sim/types.ts';

/** Wire form: [shapes, rows]; a row is [id, shapeIndex, r, g, b, motion, hidden, playerId|-1, px, py, pz, qx, qy, qz, qw]. */
export type PackedDescriptors = [unknown[], number[][]];

const MOTIONS = ['static', 'dynamic', 'kinematic'] as const;
const ROW_LENGTH = 15;
/** Nesting limit of compound shapes on the wire. */
const MAX_SHAPE_DEPTH = 4;
/** Generous caps that keep a hostile or broken peer from allocating without bound. */
const MAX_ARRAY_VALUES = 12_000_000;
const MAX_COMPOUND_PARTS = 4096;

type PlainShape = Record<string, unknown>;

function plainArray(values: ArrayLike<number>): number[] {
  return Array.from(values);
}

function toPlainShape(spec: ShapeSpec): PlainShape {
  switch (spec.kind) {
    case 'box':
      return { kind: 'box', halfExtents: { x: spec.halfExtents.x, y: spec.halfExtents.y, z: spec.halfExtents.z } };
    case 'sphere':
      return { kind: 'sphere', radius: spec.radius };
    case 'capsule':
      return { kind: 'capsule', halfHeight: spec.halfHeight, radius: spec.radius };
    case 'cylinder':
      return { kind: 'cylinder', halfHeight: spec.halfHeight, radius: spec.radius };
    case 'convexHull':
      return { kind: 'convexHull', points: plainArray(spec.points) };
    case 'mesh':
      return { kind: 'mesh', positions: plainArray(spec.positions), indices: plainArray(spec.indices) };
    case 'heightField': {
      const out: PlainShape = { kind: 'heightField', heights: plainArray(spec.heights), sampleCount: spec.sampleCount, cellSize: spec.cellSize };
      if (spec.originXz) out.originXz = { x: spec.originXz.x, z: spec.originXz.z };
      return out;
    }
    case 'compound':
      return {
        kind: 'compound',
        parts: spec.parts.map((p) => {
          const part: PlainShape = { shape: toPlainShape(p.shape) };
          if (p.position) part.position = { x: p.position.x, y: p.position.y, z: p.position.z };
          if (p.rotation) part.rotation = { x: p.rotation.x, y: p.rotation.y, z: p.rotation.z, w: p.rotation.w };
          return part;
        }),
      };
  }
}

/** Packs descriptors, sending each distinct shape once (primitives by value, others by object identity). */
export function packDescriptors(list: readonly BodyDescriptor[]): PackedDescriptors {
  const shapes: unknown[] = [];
  const byKey = new Map<string, number>();
  const byRef = new Map<object, number>();
  const rows: number[][] = [];
  for (const d of list) {
    const s = d.shape;
    let index: number | undefined;
    const primitive = s.kind === 'box' || s.kind === 'sphere' || s.kind === 'capsule' || s.kind === 'cylinder';
    const key = primitive ? JSON.stringify(toPlainShape(s)) : '';
    index = primitive ? byKey.get(key) : byRef.get(s);
    if (index === undefined) {
      index = shapes.length;
      shapes.push(toPlainShape(s));
      if (primitive) byKey.set(key, index);
      else byRef.set(s, index);
    }
    const motion = MOTIONS.indexOf(d.motion);
    rows.push([
      d.id,
      index,
      d.color[0],
      d.color[1],
      d.color[2],
      motion < 0 ? 1 : motion,
      d.hidden ? 1 : 0,
      d.playerId === undefined ? -1 : d.playerId,
      d.position.x,
      d.position.y,
      d.position.z,
      d.rotation.x,
      d.rotation.y,
      d.rotation.z,
      d.rotation.w,
    ]);
  }
  return [shapes, rows];
}

function fail(path: string, message: string): never {
  throw new Error(`descriptor ${path}: ${message}`);
}

function isObject(v: unknown): v is Record<string, unknown> {
  return v !== null && typeof v === 'object' && !Array.isArray(v) && !ArrayBuffer.isView(v);
}

function finite(v: unknown, path: string): number {
  if (typeof v !== 'number' || !Number.isFinite(v)) fail(path, `must be a finite number, got ${describeValue(v)}`);
  return v;
}

function positive(v: unknown, path: string): number {
  const n = finite(v, path);
  if (n <= 0) fail(path, `must be > 0, got ${n}`);
  return n;
}

function vec3(v: unknown, path: string): { x: number; y: number; z: number } {
  if (!isObject(v)) fail(path, 'must be an {x, y, z} object');
  return { x: finite(v.x, `${path}.x`), y: finite(v.y, `${path}.y`), z: finite(v.z, `${path}.z`) };
}

function quat(v: unknown, path: string): { x: number; y: number; z: number; w: number } {
  if (!isObject(v)) fail(path, 'must be an {x, y, z, w} object');
  return { x: finite(v.x, `${path}.x`), y: finite(v.y, `${path}.y`), z: finite(v.z, `${path}.z`), w: finite(v.w, `${path}.w`) };
}

function numbers(v: unknown, path: string, multipleOf: number): number[] {
  if (!Array.isArray(v)) fail(path, 'must be an array of numbers');
  if (v.length > MAX_ARRAY_VALUES) fail(path, `has ${v.length} values (limit ${MAX_ARRAY_VALUES})`);
  if (v.length % multipleOf !== 0) fail(path, `length ${v.length} is not a multiple of ${multipleOf}`);
  for (let i = 0; i < v.length; i++) if (typeof v[i] !== 'number' || !Number.isFinite(v[i])) fail(`${path}[${i}]`, 'must be a finite number');
  return v as number[];
}

/** Checks an untrusted shape description and returns it as a ShapeSpec; throws a clear Error naming the field. */
export function parseShape(raw: unknown, path = 'shape', depth = 0): ShapeSpec {
  if (!isObject(raw)) fail(path, 'must be an object');
  switch (raw.kind) {
    case 'box':
      return { kind: 'box', halfExtents: (() => {
        const h = vec3(raw.halfExtents, `${path}.halfExtents`);
        if (h.x <= 0 || h.y <= 0 || h.z <= 0) fail(`${path}.halfExtents`, 'components must be > 0');
        return h;
      })() };
    case 'sphere':
      return { kind: 'sphere', radius: positive(raw.radius, `${path}.radius`) };
    case 'capsule':
    case 'cylinder':
      return { kind: raw.kind, halfHeight: positive(raw.halfHeight, `${path}.halfHeight`), radius: positive(raw.radius, `${path}.radius`) };
    case 'convexHull': {
      const points = numbers(raw.points, `${path}.points`, 3);
      if (points.length < 9) fail(`${path}.points`, 'needs at least 3 points');
      return { kind: 'convexHull', points };
    }
    case 'mesh': {
      const positions = numbers(raw.positions, `${path}.positions`, 3);
      const indices = numbers(raw.indices, `${path}.indices`, 3);
      const vertexCount = positions.length / 3;
      for (let i = 0; i < indices.length; i++) {
        const ix = indices[i];
        if (!Number.isInteger(ix) || ix < 0 || ix >= vertexCount) fail(`${path}.indices[${i}]`, `must be a vertex index < ${vertexCount}, got ${ix}`);
      }
      return { kind: 'mesh', positions, indices };
    }
    case 'heightField': {
      const sampleCount = raw.sampleCount;
      if (typeof sampleCount !== 'number' || !Number.isInteger(sampleCount) || sampleCount < 2 || sampleCount > 4096) fail(`${path}.sampleCount`, 'must be an integer in [2, 4096]');
      const heights = numbers(raw.heights, `${path}.heights`, 1);
      if (heights.length !== sampleCount * sampleCount) fail(`${path}.heights`, `needs ${sampleCount * sampleCount} samples, got ${heights.length}`);
      const spec: ShapeSpec = { kind: 'heightField', heights, sampleCount, cellSize: positive(raw.cellSize, `${path}.cellSize`) };
      if (raw.originXz !== undefined && raw.originXz !== null) {
        if (!isObject(raw.originXz)) fail(`${path}.originXz`, 'must be an {x, z} object');
        spec.originXz = { x: finite(raw.originXz.x, `${path}.originXz.x`), z: finite(raw.originXz.z, `${path}.originXz.z`) };
      }
      return spec;
    }
    case 'compound': {
      if (depth >= MAX_SHAPE_DEPTH) fail(path, `compound shapes nest deeper than ${MAX_SHAPE_DEPTH}`);
      if (!Array.isArray(raw.parts) || raw.parts.length === 0 || raw.parts.length > MAX_COMPOUND_PARTS) fail(`${path}.parts`, `must be an array of 1..${MAX_COMPOUND_PARTS} parts`);
      const parts = raw.parts.map((p: unknown, i: number) => {
        const pp = `${path}.parts[${i}]`;
        if (!isObject(p)) fail(pp, 'must be an object');
        const part: { shape: ShapeSpec; position?: { x: number; y: number; z: number }; rotation?: { x: number; y: number; z: number; w: number } } = {
          shape: parseShape(p.shape, `${pp}.shape`, depth + 1),
        };
        if (p.position !== undefined && p.position !== null) part.position = vec3(p.position, `${pp}.position`);
        if (p.rotation !== undefined && p.rotation !== null) part.rotation = quat(p.rotation, `${pp}.rotation`);
        return part;
      });
      return { kind: 'compound', parts };
    }
    default:
      return fail(`${path}.kind`, `unknown shape kind ${describeValue(raw.kind)}`);
  }
}

/** Checks and unpacks the wire form; throws a clear Error (naming the row and field) on anything malformed. */
export function unpackDescriptors(raw: unknown, what = 'descriptors'): BodyDescriptor[] {
  if (!Array.isArray(raw) || raw.length !== 2 || !Array.isArray(raw[0]) || !Array.isArray(raw[1])) fail(what, 'must be [shapes, rows]');
  const shapes = (raw[0] as unknown[]).map((s, i) => parseShape(s, `${what}.shapes[${i}]`));
  const rows = raw[1] as unknown[];
  const out: BodyDescriptor[] = [];
  for (let i = 0; i < rows.length; i++) {
    const path = `${what}.rows[${i}]`;
    const row = rows[i];
    if (!Array.isArray(row) || row.length !== ROW_LENGTH) fail(path, `must be an array of ${ROW_LENGTH} numbers`);
    for (let f = 0; f < ROW_LENGTH; f++) finite(row[f], `${path}[${f}]`);
    const [id, shapeIndex, r, g, b, motion, hidden, playerId, px, py, pz, qx, qy, qz, qw] = row as number[];
    if (!Number.isInteger(id) || id < 0 || id > 0x7fff_ffff) fail(`${path}.id`, `must be an integer in [0, 2^31), got ${id}`);
    if (!Number.isInteger(shapeIndex) || shapeIndex < 0 || shapeIndex >= shapes.length) fail(`${path}.shape`, `index ${shapeIndex} is not in the shape table (${shapes.length})`);
    if (!Number.isInteger(motion) || motion < 0 || motion > 2) fail(`${path}.motion`, `must be 0, 1 or 2, got ${motion}`);
    if (hidden !== 0 && hidden !== 1) fail(`${path}.hidden`, `must be 0 or 1, got ${hidden}`);
    if (!Number.isInteger(playerId) || playerId < -1) fail(`${path}.playerId`, `must be an integer ≥ -1, got ${playerId}`);
    const d: BodyDescriptor = {
      id,
      shape: shapes[shapeIndex],
      color: [r, g, b],
      motion: MOTIONS[motion],
      hidden: hidden === 1,
      position: { x: px, y: py, z: pz },
      rotation: { x: qx, y: qy, z: qz, w: qw },
    };
    if (playerId >= 0) d.playerId = playerId;
    out.push(d);
  }
  return out;
}
