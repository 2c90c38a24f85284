// Binary form of body records for byte checkpoints: shape specs (every kind, compounds recursively), creation pose,
// options as JSON, colour. Scene bodies are stored by id only: every simulation of the same setup builds them.
import { IDENTITY_QUAT, type CompoundPart, type ShapeSpec } from '../physics/index.ts';
import { playerColor, type BodyKind, type BodyRecord } from './body-registry.ts';
import { ByteReader, ByteWriter } from '../byte-io.ts';
import type { Rgb, SpawnOptions } from './scenario.ts';
import type { BodyDescriptor } from './types.ts';

const SHAPE_CODES = { box: 0, sphere: 1, capsule: 2, cylinder: 3, convexHull: 4, mesh: 5, heightField: 6, compound: 7 } as const;
const SHAPE_KINDS = Object.keys(SHAPE_CODES) as ShapeSpec['kind'][];
const KIND_CODES = { scene: 0, spawn: 1, bullet: 2, character: 3 } as const;
const KINDS = Object.keys(KIND_CODES) as BodyKind[];
const MOTIONS = ['static', 'dynamic', 'kinematic'] as const;
const MAX_COMPOUND_DEPTH = 8;

/** Writes a shape spec. */
export function writeShape(w: ByteWriter, spec: ShapeSpec): void {
  w.u8(SHAPE_CODES[spec.kind]);
  switch (spec.kind) {
    case 'box':
      w.f64(spec.halfExtents.x).f64(spec.halfExtents.y).f64(spec.halfExtents.z);
      break;
    case 'sphere':
      w.f64(spec.radius);
      break;
    case 'capsule':
    case 'cylinder':
      w.f64(spec.halfHeight).f64(spec.radius);
      break;
    case 'convexHull':
      w.f64s(spec.points);
      break;
    case 'mesh':
      w.f64s(spec.positions).u32s(spec.indices);
      break;
    case 'heightField':
      w.f64s(spec.heights).u32(spec.sampleCount).f64(spec.cellSize);
      w.u8(spec.originXz ? 1 : 0);
      if (spec.originXz) w.f64(spec.originXz.x).f64(spec.originXz.z);
      break;
    case 'compound':
      w.u32(spec.parts.length);
      for (const part of spec.parts) {
        writeShape(w, part.shape);
        w.u8(part.position ? 1 : 0);
        if (part.position) w.f64(part.position.x).f64(part.position.y).f64(part.position.z);
        w.u8(part.rotation ? 1 : 0);
        if (part.rotation) w.f64(part.rotation.x).f64(part.rotation.y).f64(part.rotation.z).f64(part.rotation.w);
      }
      break;
  }
}

/** Reads a shape spec (values are validated again by the physics layer when the body is built). */
export function readShape(r: ByteReader, depth = 0): ShapeSpec {
  if (depth > MAX_COMPOUND_DEPTH) throw new Error('checkpoint: compound shapes nest too deep');
  const kind = SHAPE_KINDS[r.u8('shape kind')];
  switch (kind) {
    case 'box':
      return { kind, halfExtents: { x: r.f64('box'), y: r.f64('box'), z: r.f64('box') } };
    case 'sphere':
      return { kind, radius: r.f64('sphere radius') };
    case 'capsule':
    case 'cylinder':
      return { kind, halfHeight: r.f64(`${kind} halfHeight`), radius: r.f64(`${kind} radius`) };
    case 'convexHull':
      return { kind, points: r.f64s('hull points') };
    case 'mesh':
      return { kind, positions: r.f64s('mesh positions'), indices: r.u32s('mesh indices') };
    case 'heightField': {
      const heights = r.f64s('heights');
      const sampleCount = r.u32('sampleCount');
      const cellSize = r.f64('cellSize');
      const spec: ShapeSpec = { kind, heights, sampleCount, cellSize };
      if (r.u8('origin flag')) spec.originXz = { x: r.f64('origin x'), z: r.f64('origin z') };
      return spec;
    }
    case 'compound': {
      const n = r.count('compound part count', 3);
      const parts: CompoundPart[] = [];
      for (let i = 0; i < n; i++) {
        const part: CompoundPart = { shape: readShape(r, depth + 1) };
        if (r.u8('part position flag')) part.position = { x: r.f64('part x'), y: r.f64('part y'), z: r.f64('part z') };
        if (r.u8('part rotation flag')) part.rotation = { x: r.f64('part qx'), y: r.f64('part qy'), z: r.f64('part qz'), w: r.f64('part qw') };
        parts.push(part);
      }
      return { kind, parts };
    }
    default:
      throw new Error('checkpoint: unknown shape kind');
  }
}

/** The JSON-able part of spawn options (sensor callbacks are never stored: bodies spawned mid-run cannot have them). */
function optionsJson(opts: Readonly<SpawnOptions>, id: number): string {
  const { sensor: _sensor, ...rest } = opts;
  const strict = (key: string, value: unknown): unknown => {
    const t = typeof value;
    if (t === 'function' || t === 'symbol' || t === 'bigint' || (t === 'number' && !Number.isFinite(value)) || ArrayBuffer.isView(value)) {
      throw new Error(`"${key}" holds ${t === 'number' ? String(value) : ArrayBuffer.isView(value) ? 'a typed array' : `a ${t}`}`);
    }
    return value;
  };
  try {
    return JSON.stringify(rest, strict);
  } catch (err) {
    throw new Error(`saveCheckpointBytes: body ${id}'s options (userData) are not plain JSON data: ${(err as Error).message}`);
  }
}

/** Writes one record: scene bodies by id only, characters by player, everything else in full. */
export function writeRecord(w: ByteWriter, rec: BodyRecord): void {
  w.u32(rec.id).u32(rec.joltId).u8(KIND_CODES[rec.kind]);
  if (rec.kind === 'scene') return;
  w.f64(rec.position.x).f64(rec.position.y).f64(rec.position.z);
  if (rec.kind === 'character') {
    w.u32(rec.descriptor.playerId!).u32PrefixedString(rec.opts.name ?? '');
    return;
  }
  w.f64(rec.rotation.x).f64(rec.rotation.y).f64(rec.rotation.z).f64(rec.rotation.w);
  writeShape(w, rec.spec);
  w.u32PrefixedString(optionsJson(rec.opts, rec.id));
  const d = rec.descriptor;
  w.u8(MOTIONS.indexOf(d.motion)).u8(d.hidden ? 1 : 0).f64(d.color[0]).f64(d.color[1]).f64(d.color[2]);
}

/** Recipe bytes of a record, for "is this live body the saved one" comparisons. */
export function recordBytes(rec: BodyRecord): Uint8Array {
  const w = new ByteWriter();
  writeRecord(w, rec);
  return w.finish();
}

/** What a reader needs to rebuild scene and character records. */
export interface RecordContext {
  sceneRecord(id: number): BodyRecord | undefined;
  characterShape: ShapeSpec;
  /** Join index of a saved player (for its colour). */
  joinIndexOf(playerId: number): number | undefined;
}

/** Reads one record written by writeRecord. */
export function readRecord(r: ByteReader, ctx: RecordContext): BodyRecord {
  const id = r.u32('body id');
  const joltId = r.u32('jolt id');
  const kind = KINDS[r.u8('body kind')];
  if (!kind) throw new Error(`checkpoint: body ${id} has an unknown kind`);
  if (kind === 'scene') {
    const rec = ctx.sceneRecord(id);
    if (!rec || rec.joltId !== joltId) throw new Error(`checkpoint: scene body ${id} does not match this simulation's build (different scenario version?)`);
    return rec;
  }
  const position = { x: r.finite('x'), y: r.finite('y'), z: r.finite('z') };
  if (kind === 'character') {
    const playerId = r.u32('player id');
    const name = r.u32PrefixedString('player name');
    const joinIndex = ctx.joinIndexOf(playerId);
    if (joinIndex === undefined) throw new Error(`checkpoint: character body ${id} belongs to player ${playerId}, who is not in the checkpoint`);
    const descriptor: BodyDescriptor = { id, shape: ctx.characterShape, color: playerColor(joinIndex), motion: 'kinematic', hidden: false, playerId, position, rotation: { ...IDENTITY_QUAT } };
    return Object.freeze({ id, joltId, kind, spec: ctx.characterShape, position, rotation: { ...IDENTITY_QUAT }, opts: Object.freeze({ name }), descriptor: Object.freeze(descriptor) });
  }
  const rotation = { x: r.finite('qx'), y: r.finite('qy'), z: r.finite('qz'), w: r.finite('qw') };
  const spec = readShape(r);
  let opts: SpawnOptions;
  try {
    opts = JSON.parse(r.u32PrefixedString('body options')) as SpawnOptions;
  } catch (err) {
    throw new Error(`checkpoint: body ${id}'s options are not valid JSON (${(err as Error).message})`);
  }
  if (opts === null || typeof opts !== 'object' || Array.isArray(opts)) throw new Error(`checkpoint: body ${id}'s options are not an object`);
  const motion = MOTIONS[r.u8('motion')];
  if (!motion) throw new Error(`checkpoint: body ${id} has an unknown motion kind`);
  const hidden = r.u8('hidden') === 1;
  const color: Rgb = [r.finite('red'), r.finite('green'), r.finite('blue')];
  const descriptor: BodyDescriptor = { id, shape: spec, color, motion, hidden, position, rotation };
  return Object.freeze({ id, joltId, kind, spec, position, rotation, opts: Object.freeze(opts), descriptor: Object.freeze(descriptor) });
}
