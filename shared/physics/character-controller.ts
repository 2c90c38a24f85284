// CharacterController (seed §25.13): Jolt CharacterVirtual move-and-slide with stairs, floor stick, jumping and
// ground state, plus a kinematic inner body on the character's layer so rays and sensors see it.
// `position` is the character's feet; the capsule stands on it (height 2·(halfHeight + radius)).
import { checkVec3 } from '../physics-data/shape-spec.ts';
import type { Vec3Like } from '../physics-data/vectors.ts';
import type { BodyHandle } from './body-handle.ts';
import type { JoltModule } from './jolt-backend.ts';
import { checkNoCollideGroup } from './body-slots.ts';
import { characterParts } from './character-parts.ts';
import { assertGroupBits, CollisionLayer, packObjectLayer } from './layers.ts';
import { worldInternals, type PhysicsWorld, type WorldInternals } from './physics-world.ts';
import { restoreStateBytes, saveStateBytes, type JoltStateRecorder } from './state-recorder.ts';

type J = JoltModule;

/** Where the character stands: 'ground' walkable, 'steep' too steep to stand on, 'air', or 'unsupported'. */
export type GroundState = 'ground' | 'steep' | 'air' | 'unsupported';

/** Options of a CharacterController; sizes in metres, angles in degrees. */
export interface CharacterOptions {
  radius?: number;
  /** Half-length of the capsule's cylinder part. */
  halfHeight?: number;
  /** Feet position. */
  position: Vec3Like;
  layer?: number;
  /** Default All, so triggers notice the character (seed §25.12). */
  mask?: number;
  /** Steepest walkable slope; default 45°. */
  maxSlopeDegrees?: number;
  /** Highest step walked up automatically; default 0.4 m. */
  stepUpHeight?: number;
  /** How far the character snaps down to keep contact on slopes and stairs; default 0.5 m. */
  stickToFloorDistance?: number;
  /** Mass used when pushing dynamic bodies; default 70 kg. */
  massKg?: number;
  /** Create the kinematic inner body (default true). */
  innerBody?: boolean;
  userData?: unknown;
  name?: string;
  /** The inner body's no-collide group: bodies sharing it (e.g. this player's bullets) never touch the capsule. */
  noCollideGroup?: number;
}

const GROUND_STATES: Record<number, GroundState> = {};

/** The ids the constructor call in progress recreates its inner body under: set only by recreateCharacter. */
let restoringIds: { id: number; joltId: number } | undefined;

/**
 * Recreates a saved character with its inner body under the saved stable id and Jolt BodyID (checkpoint restore).
 * Not public API: shared/sim reaches it through shared/physics/internal.ts.
 */
export function recreateCharacter(world: PhysicsWorld, opts: CharacterOptions, ids: { id: number; joltId: number }): CharacterController {
  restoringIds = ids;
  try {
    return new CharacterController(world, opts);
  } finally {
    restoringIds = undefined;
  }
}

/** A move-and-slide character. Set `velocity.x/z` each tick, call move(dtSeconds), read the results. */
export class CharacterController {
  /** Desired/current velocity (m/s). x/z are yours to set; y is gravity and jumps, resolved by move(). */
  readonly velocity: Vec3Like = { x: 0, y: 0, z: 0 };
  readonly radius: number;
  readonly halfHeight: number;
  readonly layer: number;
  readonly mask: number;
  /** The kinematic inner body (undefined when innerBody: false). */
  readonly body: BodyHandle | undefined;
  private readonly world: PhysicsWorld;
  private readonly J: J;
  private readonly character: InstanceType<J['CharacterVirtual']>;
  private readonly update: InstanceType<J['ExtendedUpdateSettings']>;
  private readonly bpFilter: InstanceType<J['DefaultBroadPhaseLayerFilter']>;
  private readonly objFilter: InstanceType<J['DefaultObjectLayerFilter']>;
  private readonly bodyFilter: InstanceType<J['BodyFilter']>;
  private readonly shapeFilter: InstanceType<J['ShapeFilter']>;
  private readonly scratch: InstanceType<J['Vec3']>;
  private readonly internals: WorldInternals;
  private jumpRequested = 0;
  private destroyed = false;
  private readonly disposer: () => void;

  constructor(world: PhysicsWorld, opts: CharacterOptions) {
    const restoreIds = restoringIds;
    restoringIds = undefined;
    const internals = worldInternals(world);
    this.internals = internals;
    const what = `CharacterController${opts.name ? ` "${opts.name}"` : ''}`;
    const J = world.jolt;
    this.world = world;
    this.J = J;
    this.radius = positive(opts.radius ?? 0.35, what, 'radius');
    this.halfHeight = positive(opts.halfHeight ?? 0.6, what, 'halfHeight');
    checkVec3(opts.position, what, 'position');
    this.layer = opts.layer ?? CollisionLayer.Player;
    this.mask = opts.mask ?? CollisionLayer.All;
    assertGroupBits(this.layer, `${what}: layer`);
    assertGroupBits(this.mask, `${what}: mask`);
    const slope = finiteIn(opts.maxSlopeDegrees ?? 45, 0, 89, what, 'maxSlopeDegrees');
    const stepUp = finiteIn(opts.stepUpHeight ?? 0.4, 0, 10, what, 'stepUpHeight');
    const stick = finiteIn(opts.stickToFloorDistance ?? 0.5, 0, 10, what, 'stickToFloorDistance');
    const mass = positive(opts.massKg ?? 70, what, 'massKg');
    if (opts.noCollideGroup !== undefined) checkNoCollideGroup(opts.noCollideGroup, what);
    if (restoreIds && world.getBody(restoreIds.id)) throw new Error(`${what}: stable id ${restoreIds.id} is already in use`);
    world.ensureRoom(16 * 1024, what);

    const centreY = this.halfHeight + this.radius;
    const parts = characterParts(world);
    const shape = parts.shape(this.halfHeight, this.radius); // shared by the world's characters of this size
    const identity = new J.Quat(0, 0, 0, 1); // copied, freed below

    const settings = new J.CharacterVirtualSettings(); // freed after the character is built
    settings.mMass = mass;
    settings.mMaxSlopeAngle = (slope * Math.PI) / 180;
    settings.mShape = shape;
    if (opts.innerBody !== false) {
      settings.mInnerBodyShape = shape;
      settings.mInnerBodyLayer = packObjectLayer(J, this.layer, this.mask);
    }
    const up = new J.Vec3(0, 1, 0); // copied into the plane, freed below
    const plane = new J.Plane(up, -(centreY - this.halfHeight)); // bottom hemisphere supports; copied, freed below
    settings.mSupportingVolume = plane;
    J.destroy(up);
    J.destroy(plane);
    const pos = new J.RVec3(opts.position.x, opts.position.y, opts.position.z); // copied, freed below
    // Jolt picks the inner body's BodyID itself: steer it to the deterministic one (see body-slots.ts).
    const innerJoltId = opts.innerBody !== false ? internals.slots.prepareJoltChosen(restoreIds?.joltId) : 0;
    this.character = new J.CharacterVirtual(settings, pos, identity, world.system); // owned here; destroyed in destroy()
    this.character.AddRef(); // keep Jolt's ref-counting from ever freeing it behind our back
    J.destroy(pos);
    J.destroy(identity);
    J.destroy(settings);

    // Read-only during updates: shared by the world's characters (character-parts.ts), never freed here.
    this.update = parts.update(stepUp, stick);
    const filters = parts.filters(packObjectLayer(J, this.layer, this.mask));
    this.bpFilter = filters.bp;
    this.objFilter = filters.obj;
    this.bodyFilter = parts.bodyFilter;
    this.shapeFilter = parts.shapeFilter;
    this.scratch = new J.Vec3(0, 0, 0); // owned here

    if (opts.innerBody !== false) {
      const innerId = this.character.GetInnerBodyID();
      internals.slots.confirmJoltChosen(innerJoltId, innerId.GetIndexAndSequenceNumber());
      const inner = world.system.GetBodyLockInterfaceNoLock().TryGetBody(innerId);
      if (opts.noCollideGroup !== undefined) internals.slots.setNoCollideGroup(inner, opts.noCollideGroup);
      this.body = internals.track(inner, {
        motion: 'kinematic',
        layer: this.layer,
        mask: this.mask,
        isSensor: false,
        role: 'character',
        shape: { kind: 'capsule', halfHeight: this.halfHeight, radius: this.radius },
        opts: { userData: opts.userData, name: opts.name },
      }, restoreIds?.id);
    }
    this.disposer = () => this.destroy();
    internals.disposers.add(this.disposer);
    if (GROUND_STATES[J.EGroundState_OnGround] === undefined) {
      GROUND_STATES[J.EGroundState_OnGround] = 'ground';
      GROUND_STATES[J.EGroundState_OnSteepGround] = 'steep';
      GROUND_STATES[J.EGroundState_NotSupported] = 'unsupported';
      GROUND_STATES[J.EGroundState_InAir] = 'air';
    }
  }

  private live(): InstanceType<J['CharacterVirtual']> {
    if (this.destroyed) throw new Error('CharacterController was destroyed');
    return this.character;
  }

  /**
   * Advances the character by dtSeconds: folds gravity into velocity.y (fall speed reset while grounded), applies
   * a pending jump, sweeps with ExtendedUpdate (slide, stairs, floor stick) and writes back the resolved velocity.
   */
  move(dtSeconds: number): void {
    const ch = this.live();
    if (!Number.isFinite(dtSeconds) || dtSeconds <= 0) throw new Error(`CharacterController.move: dtSeconds must be > 0, got ${dtSeconds}`);
    const v = this.velocity;
    if (!Number.isFinite(v.x) || !Number.isFinite(v.y) || !Number.isFinite(v.z)) {
      throw new Error(`CharacterController.move: velocity must be finite, got (${v.x}, ${v.y}, ${v.z})`);
    }
    const gravity = this.internals.gravity; // the world's copy of Jolt's gravity (float32 values, a world-owned Vec3)
    const grounded = ch.GetGroundState() === this.J.EGroundState_OnGround;
    if (this.jumpRequested > 0) {
      v.y = this.jumpRequested;
      this.jumpRequested = 0;
    } else if (grounded && v.y <= 0) {
      const gv = ch.GetGroundVelocity(); // moving platforms carry the character
      v.y = gv.GetY();
    }
    v.y += gravity.y * dtSeconds;
    this.scratch.Set(v.x, v.y, v.z);
    ch.SetLinearVelocity(this.scratch);
    ch.ExtendedUpdate(dtSeconds, gravity.vec, this.update, this.bpFilter, this.objFilter, this.bodyFilter, this.shapeFilter, this.internals.tempAllocator);
    const out = ch.GetLinearVelocity();
    v.x = out.GetX();
    v.y = out.GetY();
    v.z = out.GetZ();
  }

  /** Starts a jump at `speedMetresPerSecond` if grounded; returns whether it did. */
  jump(speedMetresPerSecond: number): boolean {
    const ch = this.live();
    if (!Number.isFinite(speedMetresPerSecond) || speedMetresPerSecond <= 0) {
      throw new Error(`CharacterController.jump: speed must be a finite number > 0, got ${speedMetresPerSecond}`);
    }
    if (ch.GetGroundState() !== this.J.EGroundState_OnGround) return false;
    this.jumpRequested = speedMetresPerSecond;
    return true;
  }

  /** Feet position (m), a copy. */
  get position(): Vec3Like {
    const p = this.live().GetPosition(); // reused temporary
    return { x: p.GetX(), y: p.GetY(), z: p.GetZ() };
  }

  /** Copies the feet position (m) into `out` and returns it: no object made (read for every character every tick). */
  positionInto(out: Vec3Like): Vec3Like {
    const p = this.live().GetPosition(); // reused temporary
    out.x = p.GetX();
    out.y = p.GetY();
    out.z = p.GetZ();
    return out;
  }

  /** Teleports the character (feet position); velocity is kept. */
  setPosition(pos: Vec3Like): void {
    const ch = this.live();
    checkVec3(pos, 'CharacterController.setPosition', 'position');
    const p = new this.J.RVec3(pos.x, pos.y, pos.z); // copied, freed at once
    ch.SetPosition(p);
    this.J.destroy(p);
  }

  /** Standing on walkable ground. */
  get isGrounded(): boolean {
    return this.live().GetGroundState() === this.J.EGroundState_OnGround;
  }

  /** Ground state after the last move. */
  get groundState(): GroundState {
    return GROUND_STATES[this.live().GetGroundState()] ?? 'air';
  }

  /** Normal of the ground contact (zero vector in the air). */
  get groundNormal(): Vec3Like {
    const n = this.live().GetGroundNormal(); // reused temporary
    return { x: n.GetX(), y: n.GetY(), z: n.GetZ() };
  }

  /** Velocity of what the character stands on (a moving platform), zero in the air; add it to ride platforms. */
  get groundVelocity(): Vec3Like {
    const v = this.live().GetGroundVelocity(); // reused temporary
    return { x: v.GetX(), y: v.GetY(), z: v.GetZ() };
  }

  /** Copies the ground's velocity (m/s, zero in the air) into `out` and returns it: no object made. */
  groundVelocityInto(out: Vec3Like): Vec3Like {
    const v = this.live().GetGroundVelocity(); // reused temporary
    out.x = v.GetX();
    out.y = v.GetY();
    out.z = v.GetZ();
    return out;
  }

  /** Whether a jump is queued for the next move(). */
  get jumpPending(): boolean {
    return this.jumpRequested > 0;
  }

  /** Writes the CharacterVirtual's state (position, velocity, contacts) plus our pending jump. */
  saveTo(recorder: JoltStateRecorder): void {
    this.live().SaveState(recorder);
  }

  /** Reads what saveTo wrote. */
  restoreFrom(recorder: JoltStateRecorder): void {
    this.live().RestoreState(recorder);
  }

  /** The full state as bytes: Jolt's character state + our velocity and pending jump. */
  saveState(): Uint8Array {
    const jolt = saveStateBytes(this.J, (r) => this.saveTo(r));
    const out = new Uint8Array(jolt.length + 32);
    const view = new DataView(out.buffer);
    view.setFloat64(0, this.velocity.x, true);
    view.setFloat64(8, this.velocity.y, true);
    view.setFloat64(16, this.velocity.z, true);
    view.setFloat64(24, this.jumpRequested, true);
    out.set(jolt, 32);
    return out;
  }

  /** Restores what saveState returned (throws on a short or corrupt buffer). */
  restoreState(bytes: Uint8Array): void {
    this.live();
    if (!(bytes instanceof Uint8Array) || bytes.length < 32) throw new Error('CharacterController.restoreState: buffer too short');
    const view = new DataView(bytes.buffer, bytes.byteOffset, bytes.byteLength);
    const ok = restoreStateBytes(this.J, bytes.subarray(32), (r) => this.restoreFrom(r));
    if (!ok) throw new Error('CharacterController.restoreState: the state bytes are truncated or corrupt');
    this.velocity.x = view.getFloat64(0, true);
    this.velocity.y = view.getFloat64(8, true);
    this.velocity.z = view.getFloat64(16, true);
    this.jumpRequested = view.getFloat64(24, true);
  }

  /** The pending jump speed (0 if none), for checkpoints. */
  get pendingJumpSpeed(): number {
    return this.jumpRequested;
  }

  /** Sets the pending jump speed (checkpoint restore). */
  set pendingJumpSpeed(speed: number) {
    this.jumpRequested = speed;
  }

  /** Removes the character and its inner body, and frees every Jolt object it made. */
  destroy(): void {
    if (this.destroyed) return;
    this.destroyed = true;
    const internals = worldInternals(this.world);
    internals.disposers.delete(this.disposer);
    const J = this.J;
    if (this.body) internals.untrack(this.body);
    this.character.Release(); // our reference; the character (and its inner body) is freed when it reaches zero
    J.destroy(this.scratch);
  }

  /** Whether destroy() has run. */
  get isDestroyed(): boolean {
    return this.destroyed;
  }
}

function positive(v: number, what: string, field: string): number {
  if (typeof v !== 'number' || !Number.isFinite(v) || v <= 0) throw new Error(`${what}: ${field} must be a finite number > 0, got ${String(v)}`);
  return v;
}

function finiteIn(v: number, min: number, max: number, what: string, field: string): number {
  if (typeof v !== 'number' || !Number.isFinite(v) || v < min || v > max) {
    throw new Error(`${what}: ${field} must be a finite number in [${min}, ${max}], got ${String(v)}`);
  }
  return v;
}
