// The simulation's record of every body it made: how to rebuild it (shape, pose, options, Jolt BodyID) and how a
// client draws it (descriptor). Checkpoints keep these records; the world only keeps live Jolt bodies.
import type { BodyHandle, QuatLike, ShapeSpec, Vec3Like } from '../physics/index.ts';
import type { Rgb, SpawnOptions } from './scenario.ts';
import type { BodyDescriptor } from './types.ts';

/** Who made a body: the scenario (while building or during ticks), a player's gun, or a join (character capsule). */
export type BodyKind = 'scene' | 'spawn' | 'bullet' | 'character';

/** Everything needed to recreate and draw one body. Records are immutable once made. */
export interface BodyRecord {
  readonly id: number;
  readonly joltId: number;
  readonly kind: BodyKind;
  readonly spec: ShapeSpec;
  readonly position: Vec3Like;
  readonly rotation: QuatLike;
  /** Options the body was created with (colour and hidden included); unused for characters. */
  readonly opts: Readonly<SpawnOptions>;
  readonly descriptor: BodyDescriptor;
}

/** Default colours by motion kind and role. */
export const DEFAULT_COLORS = {
  static: [0.55, 0.57, 0.6] as Rgb,
  dynamic: [0.85, 0.55, 0.25] as Rgb,
  kinematic: [0.35, 0.55, 0.85] as Rgb,
  bullet: [1, 0.85, 0.2] as Rgb,
} as const;

const PLAYER_COLORS: readonly Rgb[] = [
  [0.9, 0.3, 0.3],
  [0.3, 0.75, 0.35],
  [0.3, 0.5, 0.95],
  [0.95, 0.75, 0.2],
  [0.75, 0.35, 0.9],
  [0.2, 0.8, 0.8],
  [0.95, 0.5, 0.7],
  [0.6, 0.6, 0.25],
];

/** The colour of the n-th player to join. */
export function playerColor(joinIndex: number): Rgb {
  return PLAYER_COLORS[joinIndex % PLAYER_COLORS.length];
}

function copyRgb(c: Rgb | undefined, fallback: Rgb, what: string): Rgb {
  if (c === undefined) return fallback;
  if (!Array.isArray(c) || c.length !== 3 || c.some((v) => typeof v !== 'number' || !Number.isFinite(v) || v < 0 || v > 1)) {
    throw new Error(`${what}: color must be three numbers in [0, 1]`);
  }
  return [c[0], c[1], c[2]];
}

/** Builds the immutable record of a body the world just created. */
export function makeRecord(kind: BodyKind, handle: BodyHandle, spec: ShapeSpec, position: Vec3Like, rotation: QuatLike, opts: SpawnOptions, extra: { playerId?: number; color?: Rgb } = {}): BodyRecord {
  const what = `body ${handle.id}${opts.name ? ` (${opts.name})` : ''}`;
  const fallback = kind === 'bullet' ? DEFAULT_COLORS.bullet : DEFAULT_COLORS[handle.motion];
  const pos = { x: position.x, y: position.y, z: position.z };
  const rot = { x: rotation.x, y: rotation.y, z: rotation.z, w: rotation.w };
  const descriptor: BodyDescriptor = {
    id: handle.id,
    shape: spec,
    color: copyRgb(extra.color ?? opts.color, fallback, what),
    motion: handle.motion,
    hidden: opts.hidden === true,
    position: pos,
    rotation: rot,
  };
  if (extra.playerId !== undefined) descriptor.playerId = extra.playerId;
  return Object.freeze({ id: handle.id, joltId: handle.joltId, kind, spec, position: pos, rotation: rot, opts: Object.freeze({ ...opts }), descriptor: Object.freeze(descriptor) });
}

/** Records of the live bodies, by stable id. */
export class BodyRegistry {
  private readonly records = new Map<number, BodyRecord>();

  /** Adds a record (its id must be new). */
  add(record: BodyRecord): void {
    if (this.records.has(record.id)) throw new Error(`BodyRegistry: body ${record.id} is already registered`);
    this.records.set(record.id, record);
  }

  /** Forgets a body; returns its record. */
  delete(id: number): BodyRecord | undefined {
    const r = this.records.get(id);
    this.records.delete(id);
    return r;
  }

  get(id: number): BodyRecord | undefined {
    return this.records.get(id);
  }

  has(id: number): boolean {
    return this.records.has(id);
  }

  get size(): number {
    return this.records.size;
  }

  /** Every record, ascending id. */
  all(): BodyRecord[] {
    return [...this.records.values()].sort((a, b) => a.id - b.id);
  }

  /** Replaces every record (checkpoint restore). */
  replaceAll(records: Iterable<BodyRecord>): void {
    this.records.clear();
    for (const r of records) this.records.set(r.id, r);
  }
}
