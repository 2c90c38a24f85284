// CPU bookkeeping of what the renderer draws: bodies grouped by mesh, their styles and poses, packed into
// per-instance floats (static bodies once, dynamic ones every frame). No GPU calls here, so it is unit-testable.
import type { Vec3 } from './mat4.ts';
import { INSTANCE_FLOATS } from './shaders.ts';
import type { ShapeMeshRef } from './shape-mesh.ts';

/** An RGB colour with components in [0, 1] (sRGB). */
export type Rgb = readonly [number, number, number];

/** How one body looks. */
export interface BodyStyle {
  color: Rgb;
  /** Extra self-lit brightness (0 = none; 1 doubles the lit colour), e.g. an occupied trigger zone. */
  emissive: number;
  /** InstanceFlag bits. */
  flags: number;
  /** Drawn at all (e.g. false before a body's spawn tick). */
  visible: boolean;
}

/** What the store needs to know about a new body. */
export interface BodyRegistration {
  mesh: ShapeMeshRef;
  /** Static bodies are packed once; their pose never changes. */
  isStatic: boolean;
  style: BodyStyle;
  position?: { x: number; y: number; z: number };
  rotation?: { x: number; y: number; z: number; w: number };
}

interface StoredBody {
  id: number;
  key: string;
  scale: Vec3;
  isStatic: boolean;
  style: BodyStyle;
  /** px, py, pz, qx, qy, qz, qw */
  pose: Float64Array;
}

/** A run of instances of one mesh inside a packed buffer. */
export interface InstanceRange {
  key: string;
  first: number;
  count: number;
}

/** Packed instance floats plus the run of each mesh. */
export interface PackedInstances {
  data: Float32Array<ArrayBuffer>;
  count: number;
  ranges: InstanceRange[];
}

/** Bodies by id, grouped by mesh key; reports which meshes appear and disappear. */
export class InstanceStore {
  private readonly bodies = new Map<number, StoredBody>();
  private readonly keyUsers = new Map<string, number>();
  private staticDirty = true;
  private sortedDirty = true;
  private sortedStatic: StoredBody[] = [];
  private sortedDynamic: StoredBody[] = [];
  private dynamicData = new Float32Array(INSTANCE_FLOATS * 64);

  /** Number of bodies held. */
  get size(): number {
    return this.bodies.size;
  }

  /** Whether a body with this id is held. */
  has(id: number): boolean {
    return this.bodies.has(id);
  }

  /** Ids of all held bodies, ascending. */
  ids(): number[] {
    return [...this.bodies.keys()].sort((a, b) => a - b);
  }

  /** Adds a body; returns true when its mesh key is new (the caller uploads the mesh). Throws on a duplicate id. */
  add(id: number, reg: BodyRegistration): boolean {
    if (!Number.isInteger(id) || id < 0) throw new Error(`renderer: body id must be a non-negative integer, got ${String(id)}`);
    if (this.bodies.has(id)) throw new Error(`renderer: body ${id} is already registered`);
    const pose = new Float64Array([0, 0, 0, 0, 0, 0, 1]);
    const body: StoredBody = { id, key: reg.mesh.key, scale: reg.mesh.scale, isStatic: reg.isStatic, style: { ...reg.style }, pose };
    this.bodies.set(id, body);
    if (reg.position || reg.rotation) {
      const p = reg.position ?? { x: 0, y: 0, z: 0 };
      const q = reg.rotation ?? { x: 0, y: 0, z: 0, w: 1 };
      this.writePose(body, p.x, p.y, p.z, q.x, q.y, q.z, q.w);
    }
    const users = this.keyUsers.get(body.key) ?? 0;
    this.keyUsers.set(body.key, users + 1);
    this.sortedDirty = true;
    if (reg.isStatic) this.staticDirty = true;
    return users === 0;
  }

  /** Removes a body; returns its mesh key when no body uses that mesh any more (the caller frees it). */
  remove(id: number): string | null {
    const body = this.bodies.get(id);
    if (!body) return null;
    this.bodies.delete(id);
    this.sortedDirty = true;
    if (body.isStatic) this.staticDirty = true;
    const users = (this.keyUsers.get(body.key) ?? 1) - 1;
    if (users > 0) {
      this.keyUsers.set(body.key, users);
      return null;
    }
    this.keyUsers.delete(body.key);
    return body.key;
  }

  /** Sets a body's pose (position in metres, unit quaternion). Unknown ids are ignored. */
  setPose(id: number, px: number, py: number, pz: number, qx: number, qy: number, qz: number, qw: number): void {
    const body = this.bodies.get(id);
    if (body) this.writePose(body, px, py, pz, qx, qy, qz, qw);
  }

  /** The pose last set for a body, or null. */
  pose(id: number): readonly number[] | null {
    const body = this.bodies.get(id);
    return body ? Array.from(body.pose) : null;
  }

  /** Changes part of a body's style. Unknown ids are ignored. */
  setStyle(id: number, style: Partial<BodyStyle>): void {
    const body = this.bodies.get(id);
    if (!body) return;
    const before = body.style;
    body.style = { ...before, ...style };
    const changed = before.color !== body.style.color || before.emissive !== body.style.emissive || before.flags !== body.style.flags || before.visible !== body.style.visible;
    if (changed && body.isStatic) this.staticDirty = true;
  }

  /** A body's current style, or null. */
  style(id: number): BodyStyle | null {
    return this.bodies.get(id)?.style ?? null;
  }

  /** True (once) when the static instances changed since the last packStatic(). */
  takeStaticDirty(): boolean {
    const dirty = this.staticDirty;
    this.staticDirty = false;
    return dirty;
  }

  /** Packs every visible static body (a fresh array; called only when they changed). */
  packStatic(): PackedInstances {
    this.sort();
    return pack(this.sortedStatic, new Float32Array(Math.max(1, this.sortedStatic.length) * INSTANCE_FLOATS));
  }

  /** Packs every visible dynamic/kinematic body into a reused array (valid until the next call). */
  packDynamic(): PackedInstances {
    this.sort();
    const needed = this.sortedDynamic.length * INSTANCE_FLOATS;
    if (this.dynamicData.length < needed) {
      let size = this.dynamicData.length;
      while (size < needed) size *= 2;
      this.dynamicData = new Float32Array(size);
    }
    return pack(this.sortedDynamic, this.dynamicData);
  }

  private writePose(body: StoredBody, px: number, py: number, pz: number, qx: number, qy: number, qz: number, qw: number): void {
    const p = body.pose;
    p[0] = px;
    p[1] = py;
    p[2] = pz;
    p[3] = qx;
    p[4] = qy;
    p[5] = qz;
    p[6] = qw;
    if (body.isStatic) this.staticDirty = true;
  }

  private sort(): void {
    if (!this.sortedDirty) return;
    // Group by mesh key (first appearance in id order), then by id: a stable draw order every frame.
    const all = [...this.bodies.values()].sort((a, b) => a.id - b.id);
    const keyOrder = new Map<string, number>();
    for (const b of all) if (!keyOrder.has(b.key)) keyOrder.set(b.key, keyOrder.size);
    const byKey = (a: StoredBody, b: StoredBody): number => (keyOrder.get(a.key) ?? 0) - (keyOrder.get(b.key) ?? 0) || a.id - b.id;
    this.sortedStatic = all.filter((b) => b.isStatic).sort(byKey);
    this.sortedDynamic = all.filter((b) => !b.isStatic).sort(byKey);
    this.sortedDirty = false;
  }
}

function pack(bodies: readonly StoredBody[], data: Float32Array<ArrayBuffer>): PackedInstances {
  const ranges: InstanceRange[] = [];
  let count = 0;
  for (const b of bodies) {
    if (!b.style.visible) continue;
    const last = ranges[ranges.length - 1];
    if (last && last.key === b.key) last.count++;
    else ranges.push({ key: b.key, first: count, count: 1 });
    const o = count * INSTANCE_FLOATS;
    const p = b.pose;
    data[o] = p[0];
    data[o + 1] = p[1];
    data[o + 2] = p[2];
    data[o + 3] = b.style.flags;
    data[o + 4] = p[3];
    data[o + 5] = p[4];
    data[o + 6] = p[5];
    data[o + 7] = p[6];
    data[o + 8] = b.scale[0];
    data[o + 9] = b.scale[1];
    data[o + 10] = b.scale[2];
    data[o + 11] = b.style.emissive;
    data[o + 12] = b.style.color[0];
    data[o + 13] = b.style.color[1];
    data[o + 14] = b.style.color[2];
    data[o + 15] = 1;
    count++;
  }
  return { data, count, ranges };
}
