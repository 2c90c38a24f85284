// What makes the drawn world read as a game, on top of the bodies the server describes: a visor on every character
// showing where it faces, a blob shadow under each moving body (on the static boxes below it) so height reads, and
// impact feedback for bullets (a spark where one bounces or trips a sensor, and a flash on the body it hit). Extra
// renderer bodies under ids no server body uses; presentation only (nothing here feeds back into the game). Shadows
// fall on static boxes, height fields and triangle meshes.
import type { SnapshotView } from '../../shared/protocol/snapshot-frame.ts';
import type { ShapeSpec } from '../../shared/physics-data/shape-spec.ts';
import { forwardFromYaw } from '../../shared/sim/controls.ts';
import type { BodyDescriptor, SimEvent } from '../../shared/sim/types.ts';
import { MeshGround, type GroundMesh } from '../render/mesh-ground.ts';
import type { RemovedBody, RenderTarget, WorldView } from './world-view.ts';

/** Decoration ids start here (server body ids are far smaller); each kind has its own block. */
const ID_BLOCK = 2 ** 40;
const VISOR_IDS = ID_BLOCK;
const SHADOW_IDS = 2 * ID_BLOCK;
const SPARK_IDS = 3 * ID_BLOCK;

/** Where the visor sits on a character: above its feet (m) and in front of its axis (m). */
const VISOR_HEIGHT_METRES = 1.45;
const VISOR_FORWARD_METRES = 0.3;
const VISOR_SHAPE: ShapeSpec = { kind: 'box', halfExtents: { x: 0.2, y: 0.07, z: 0.09 } };
const VISOR_COLOR = [0.1, 0.12, 0.16] as const;

const SHADOW_COLOR = [0.17, 0.19, 0.19] as const;
/** Shadows are drawn this far above the surface below (m): above it, thin enough to read as lying on it. */
const SHADOW_LIFT_METRES = 0.012;
const SHADOW_DROP_METRES = 60;
/** A body this far (m) above resting height counts as in the air. */
const AIRBORNE_METRES = 0.25;
/** Most shadows drawn at once (the first bodies of the view). */
const MAX_SHADOWS = 400;

const SPARK_SHAPE: ShapeSpec = { kind: 'sphere', radius: 0.16 };
const SPARK_COLOR = [1, 0.82, 0.35] as const;
const SPARK_MS = 280;
const FLASH_MS = 350;
const FLASH_EMISSIVE = 1.8;
/** A bullet is the simulation's small sphere (shared/sim/bullets.ts: radius 0.05 m). */
const BULLET_MAX_RADIUS_METRES = 0.06;
/** A bullet whose direction turns by more than this (cosine) between frames bounced off something. */
const BOUNCE_COSINE = 0.3;

/** Whether a descriptor is a bullet. */
export function isBullet(d: BodyDescriptor): boolean {
  return d.motion === 'dynamic' && d.shape.kind === 'sphere' && d.shape.radius <= BULLET_MAX_RADIUS_METRES;
}

/** The radius of a body's blob shadow (m), or 0 for shapes that get none. */
export function footprintRadius(shape: ShapeSpec): number {
  switch (shape.kind) {
    case 'box':
      return Math.hypot(shape.halfExtents.x, shape.halfExtents.z) * 0.85;
    case 'sphere':
    case 'capsule':
    case 'cylinder':
      return shape.radius;
    case 'convexHull': {
      let r = 0;
      for (let i = 0; i + 2 < shape.points.length; i += 3) r = Math.max(r, Math.hypot(shape.points[i], shape.points[i + 2]));
      return r * 0.85;
    }
    default:
      return 0;
  }
}

type HeightField = Extract<ShapeSpec, { kind: 'heightField' }>;

/** The height (m) of a static height field's surface at world (x, z), bilinear between samples; null outside it. */
export function heightFieldSurfaceY(d: BodyDescriptor, x: number, z: number): number | null {
  if (d.shape.kind !== 'heightField') return null;
  const s: HeightField = d.shape;
  const o = s.originXz ?? { x: 0, z: 0 };
  const fx = (x - d.position.x - o.x) / s.cellSize;
  const fz = (z - d.position.z - o.z) / s.cellSize;
  const n = s.sampleCount;
  if (!(fx >= 0 && fz >= 0 && fx <= n - 1 && fz <= n - 1)) return null;
  const x0 = Math.min(n - 2, Math.floor(fx));
  const z0 = Math.min(n - 2, Math.floor(fz));
  const tx = fx - x0;
  const tz = fz - z0;
  const h = (ix: number, iz: number): number => s.heights[iz * n + ix];
  const top = h(x0, z0) * (1 - tx) + h(x0 + 1, z0) * tx;
  const bottom = h(x0, z0 + 1) * (1 - tx) + h(x0 + 1, z0 + 1) * tx;
  return d.position.y + top * (1 - tz) + bottom * tz;
}

// The visible static triangle meshes, in the form MeshGround takes.
function meshesOf(descriptors: readonly BodyDescriptor[]): GroundMesh[] {
  const out: GroundMesh[] = [];
  for (const d of descriptors) {
    if (d.hidden || d.shape.kind !== 'mesh') continue;
    out.push({ positions: d.shape.positions, indices: d.shape.indices, position: d.position, rotation: d.rotation });
  }
  return out;
}

interface Tracked {
  x: number;
  y: number;
  z: number;
  /** Last frame's displacement direction (unit), or null before it moved. */
  dir: [number, number, number] | null;
  lastSparkMs: number;
}

/** The decorations of one session, mirrored into the same renderer as its world. */
export class Decorations {
  private readonly renderer: RenderTarget;
  private readonly world: WorldView;
  private readonly visors = new Set<number>();
  private readonly shadows = new Map<number, boolean>();
  private readonly sparks = new Map<number, number>();
  private readonly flashes = new Map<number, number>();
  private readonly bullets = new Map<number, Tracked>();
  private nextSpark = 0;
  private nowMs = 0;
  /** Shadow radius by body id (0: none), so a hull's points are walked once, not every frame. */
  private readonly radii = new Map<number, { descriptor: BodyDescriptor; radius: number }>();
  /** The scene's static height fields (read once per welcome, on the first frame). */
  private heightFields: BodyDescriptor[] | null = null;
  /** The scene's static triangle meshes, gridded for height queries (built once per welcome, on the first frame). */
  private meshGround: MeshGround | null = null;

  constructor(renderer: RenderTarget, world: WorldView) {
    this.renderer = renderer;
    this.world = world;
  }

  /** Places every decoration for this frame's view. */
  update(view: SnapshotView | null, nowMs: number): void {
    this.nowMs = nowMs;
    this.expire(nowMs);
    if (!view) return;
    this.placeVisors(view);
    this.placeShadowsAndTrackBullets(view);
  }

  /** Reacts to an event as it takes effect (world-view's onEvent). */
  onEvent(e: SimEvent, removed: RemovedBody | null): void {
    if (e.type === 'bodyRemoved') {
      this.bullets.delete(e.bodyId);
      this.radii.delete(e.bodyId);
      if (this.shadows.has(e.bodyId)) {
        this.renderer.removeBody(SHADOW_IDS + e.bodyId);
        this.shadows.delete(e.bodyId);
      }
      this.flashes.delete(e.bodyId);
      if (removed && isBullet(removed.descriptor) && removed.pose) this.spark(removed.pose[0], removed.pose[1], removed.pose[2]);
      return;
    }
    if (e.type === 'sensorEnter') {
      const d = this.world.descriptor(e.bodyId);
      const pose = this.renderer.store.pose(e.bodyId);
      if (!d || !isBullet(d) || !pose) return;
      // A bullet tripped a sensor (a target's): spark there and flash the body it hit.
      this.spark(pose[0], pose[1], pose[2]);
      const hit = this.nearestSolid(pose[0], pose[1], pose[2], 1.5);
      if (hit !== null) this.flash(hit);
    }
  }

  /** Removes every decoration (a new welcome). */
  clear(): void {
    for (const id of this.visors) this.renderer.removeBody(VISOR_IDS + id);
    for (const id of this.shadows.keys()) this.renderer.removeBody(SHADOW_IDS + id);
    for (const id of this.sparks.keys()) this.renderer.removeBody(id);
    for (const id of this.flashes.keys()) this.renderer.store.setStyle(id, { emissive: 0 });
    this.visors.clear();
    this.shadows.clear();
    this.sparks.clear();
    this.flashes.clear();
    this.bullets.clear();
    this.radii.clear();
    this.heightFields = null;
    this.meshGround = null;
  }

  // The highest static surface under (x, y, z) that shadows fall on: a box's top (ray cast) or a height field.
  private groundBelow(x: number, y: number, z: number): number | null {
    const occluders = this.world.occluders;
    let best: number | null = null;
    if (occluders.size > 0) {
      const hit = occluders.castRay([x, y, z], [x, y - SHADOW_DROP_METRES, z]);
      if (hit < 1) best = y - SHADOW_DROP_METRES * hit;
    }
    for (const d of this.heightFields ?? []) {
      const g = heightFieldSurfaceY(d, x, z);
      if (g !== null && g <= y && (best === null || g > best)) best = g;
    }
    const m = this.meshGround?.surfaceBelow(x, y, z) ?? null;
    if (m !== null && (best === null || m > best)) best = m;
    return best;
  }

  private placeVisors(view: SnapshotView): void {
    const present = new Set<number>();
    for (const c of view.characters) {
      present.add(c.playerId);
      const id = VISOR_IDS + c.playerId;
      if (!this.visors.has(c.playerId)) {
        this.renderer.addBody(id, { shape: VISOR_SHAPE, isStatic: false, style: { color: VISOR_COLOR, emissive: 0.2, flags: 0, visible: true } });
        this.visors.add(c.playerId);
      }
      const f = forwardFromYaw(c.yaw);
      const half = c.yaw / 2;
      this.renderer.store.setPose(id, c.position.x + f.x * VISOR_FORWARD_METRES, c.position.y + VISOR_HEIGHT_METRES, c.position.z + f.z * VISOR_FORWARD_METRES, 0, Math.sin(half), 0, Math.cos(half));
    }
    for (const playerId of [...this.visors]) {
      if (present.has(playerId)) continue;
      this.renderer.removeBody(VISOR_IDS + playerId);
      this.visors.delete(playerId);
    }
  }

  private placeShadowsAndTrackBullets(view: SnapshotView): void {
    const store = this.renderer.store;
    this.heightFields ??= this.world.staticDescriptors().filter((d) => d.shape.kind === 'heightField' && !d.hidden);
    this.meshGround ??= new MeshGround(meshesOf(this.world.staticDescriptors()));
    const canShadow = this.world.occluders.size > 0 || this.heightFields.length > 0 || this.meshGround.size > 0;
    const seen = new Set<number>();
    let drawn = 0;
    for (let i = 0; i < view.ids.length; i++) {
      const id = view.ids[i];
      const d = this.world.descriptor(id);
      if (!d || d.hidden || d.motion === 'static') continue;
      const x = view.positions[i * 3];
      const y = view.positions[i * 3 + 1];
      const z = view.positions[i * 3 + 2];
      if (isBullet(d)) {
        this.trackBullet(id, x, y, z);
        continue;
      }
      if (drawn >= MAX_SHADOWS || !canShadow) continue;
      let cached = this.radii.get(id);
      if (cached?.descriptor !== d) this.radii.set(id, (cached = { descriptor: d, radius: footprintRadius(d.shape) }));
      const radius = cached.radius;
      if (radius <= 0) continue;
      const ground = this.groundBelow(x, y, z);
      // A body resting on what is below it hides its own shadow: only bodies in the air get one (fewer to draw).
      if (ground === null || y - ground < radius + AIRBORNE_METRES) continue;
      if (!this.shadows.has(id)) {
        try {
          this.renderer.addBody(SHADOW_IDS + id, { shape: { kind: 'cylinder', radius: Math.min(radius, 4), halfHeight: 0.004 }, isStatic: false, style: { color: SHADOW_COLOR, emissive: 0, flags: 0, visible: true } });
        } catch {
          continue;
        }
        this.shadows.set(id, true);
      }
      store.setPose(SHADOW_IDS + id, x, ground + SHADOW_LIFT_METRES, z, 0, 0, 0, 1);
      if (!this.shadows.get(id)) store.setStyle(SHADOW_IDS + id, { visible: true });
      this.shadows.set(id, true);
      seen.add(id);
      drawn++;
    }
    for (const [id, visible] of this.shadows) {
      if (seen.has(id) || !visible) continue;
      store.setStyle(SHADOW_IDS + id, { visible: false });
      this.shadows.set(id, false);
    }
  }

  private trackBullet(id: number, x: number, y: number, z: number): void {
    const t = this.bullets.get(id);
    if (!t) {
      this.bullets.set(id, { x, y, z, dir: null, lastSparkMs: -Infinity });
      return;
    }
    const dx = x - t.x;
    const dy = y - t.y;
    const dz = z - t.z;
    const len = Math.hypot(dx, dy, dz);
    if (len < 1e-3) return;
    const dir: [number, number, number] = [dx / len, dy / len, dz / len];
    if (t.dir && dir[0] * t.dir[0] + dir[1] * t.dir[1] + dir[2] * t.dir[2] < BOUNCE_COSINE && this.nowMs - t.lastSparkMs > 150) {
      this.spark(t.x, t.y, t.z);
      t.lastSparkMs = this.nowMs;
    }
    t.x = x;
    t.y = y;
    t.z = z;
    t.dir = dir;
  }

  private nearestSolid(x: number, y: number, z: number, withinMetres: number): number | null {
    const view = this.world;
    let best: number | null = null;
    let bestDistance = withinMetres;
    for (const id of this.shadows.keys()) {
      const d = view.descriptor(id);
      const pose = this.renderer.store.pose(id);
      if (!d || !pose || d.playerId !== undefined) continue;
      const dist = Math.hypot(pose[0] - x, pose[1] - y, pose[2] - z);
      if (dist < bestDistance) {
        best = id;
        bestDistance = dist;
      }
    }
    return best;
  }

  private spark(x: number, y: number, z: number): void {
    const id = SPARK_IDS + this.nextSpark++;
    this.renderer.addBody(id, { shape: SPARK_SHAPE, isStatic: false, style: { color: SPARK_COLOR, emissive: 2.5, flags: 0, visible: true } });
    this.renderer.store.setPose(id, x, y, z, 0, 0, 0, 1);
    this.sparks.set(id, this.nowMs);
  }

  private flash(bodyId: number): void {
    this.renderer.store.setStyle(bodyId, { emissive: FLASH_EMISSIVE });
    this.flashes.set(bodyId, this.nowMs);
  }

  private expire(nowMs: number): void {
    for (const [id, born] of this.sparks) {
      const age = nowMs - born;
      if (age >= SPARK_MS) {
        this.renderer.removeBody(id);
        this.sparks.delete(id);
      } else this.renderer.store.setStyle(id, { emissive: 2.5 * (1 - age / SPARK_MS) });
    }
    for (const [id, born] of this.flashes) {
      const age = nowMs - born;
      if (age >= FLASH_MS) {
        this.renderer.store.setStyle(id, { emissive: 0 });
        this.flashes.delete(id);
      } else this.renderer.store.setStyle(id, { emissive: FLASH_EMISSIVE * (1 - age / FLASH_MS) });
    }
  }
}
