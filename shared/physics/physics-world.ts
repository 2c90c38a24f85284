// PhysicsWorld: one Jolt PhysicsSystem, its body registry with stable ids, the factories, stepping, sensors and
// limits. Owns every Jolt object it creates; callers only ever see plain copies and BodyHandles.
import { checkQuat, checkVec3, STATIC_ONLY_KINDS, validateShapeSpec, type ShapeSpec } from '../physics-data/shape-spec.ts';
import { IDENTITY_QUAT, type QuatLike, type Vec3Like } from '../physics-data/vectors.ts';
import { TICK_DT_SECONDS } from '../tick-rate.ts';
import { BodyHandle, type BodyRole, type JoltBody } from './body-handle.ts';
import { createJoltInstance, loadJolt, type JoltModule } from './jolt-backend.ts';
import { createLayerFilters, type LayerFilters } from './layers.ts';
import { flattenPoints, makeCreationSettings, resolveLayerMask, resolveMotion, validateBodyOptions } from './body-options.ts';
import { BodyTable } from './body-table.ts';
import * as motion from './body-motion.ts';
import { ConstraintRegistry, pointLink } from './constraints.ts';
import { RayQueries, type RayHit } from './queries.ts';
import { SensorHub, type SensorEvent } from './sensors.ts';
import { BodySlots } from './body-slots.ts';
import { BodyStateReader, type BodyStates } from './body-state-reader.ts';
import { heapGaugeOf, type HeapGauge } from './heap-gauge.ts';
import { buildValidatedShape, estimateShapeBytes, type JoltShape } from './shapes.ts';
import type { BodyOptions, MotionKind } from './types.ts';
import { ensureHeapRoom, ensureRoomForWorld, estimateStateSaveBytes, resolveWorldLimits, StepBudget, type PhysicsWorldOptions, type WorldLimits } from './world-limits.ts';

export type { PhysicsWorldOptions } from './world-limits.ts';

const MAX_STEP_SECONDS = 1 / 30;
const SUBSTEP_THRESHOLD_SECONDS = 1 / 55;
/** Heap bytes reserved per constraint (measured ≤ 700 B for a hinge). */
const CONSTRAINT_HEAP_BYTES = 4096;

type J = JoltModule;

/** What a tracked body is, as PhysicsWorld's factories and the character controller register it. */
export interface TrackInfo {
  motion: MotionKind;
  layer: number;
  mask: number;
  isSensor: boolean;
  role: BodyRole;
  shape: ShapeSpec | undefined;
  opts: BodyOptions;
}

/**
 * The part of a world that is not public API: the rest of shared/physics (characters, queries) and, through
 * shared/physics/internal.ts, shared/sim's checkpoints and tick use it. index.ts does not export it.
 */
export interface WorldInternals {
  /** Deterministic Jolt BodyID allocation (checkpoints save and restore it). */
  readonly slots: BodySlots;
  /** Per-world helpers (ray casts, characters) register cleanups here. */
  readonly disposers: Set<() => void>;
  /** The sensor hub (checkpoints export/import its open overlaps; the simulation drains it). */
  readonly sensorHub: SensorHub;
  /** Registers a Jolt body (also character inner bodies) under the next stable id, or under `id`. */
  track(body: JoltBody, info: TrackInfo, id?: number): BodyHandle;
  /** Forgets a body without touching Jolt (the character controller removes its own inner body). */
  untrack(handle: BodyHandle): void;
  /** The handle for a Jolt BodyID index+sequence number. */
  bodyByJoltId(joltId: number): BodyHandle | undefined;
  /** Restores the id counter (checkpoint restore). */
  setNextBodyId(next: number): void;
  /** Makes every bulk read read every body (true) instead of only those that can have moved (tests compare both). */
  setEveryBodyReads(every: boolean): void;
  /**
   * Gravity as Jolt holds it (float32 values) and as a Jolt Vec3 owned by the world, kept by setGravity: characters
   * read it every tick without asking Jolt.
   */
  readonly gravity: { x: number; y: number; z: number; readonly vec: InstanceType<J['Vec3']> };
  /** Jolt's temp allocator of this world (fetched once). */
  readonly tempAllocator: InstanceType<J['TempAllocator']>;
}

let internalsOf: (world: PhysicsWorld) => WorldInternals;

/** A world's internals (see WorldInternals): for shared/physics and shared/sim only. */
export function worldInternals(world: PhysicsWorld): WorldInternals {
  return internalsOf(world);
}

/** A Jolt world with stable body ids; create it with `await PhysicsWorld.create()`. */
export class PhysicsWorld {
  readonly jolt: J;
  readonly system: InstanceType<J['PhysicsSystem']>;
  readonly bodyInterface: InstanceType<J['BodyInterface']>;
  readonly filters: LayerFilters;
  readonly maxBodies: number;
  readonly minFreeHeapBytes: number;
  private readonly slots: BodySlots;
  private readonly joltInterface: InstanceType<J['JoltInterface']>;
  private readonly table = new BodyTable();
  private readonly constraints: ConstraintRegistry;
  private readonly stepBudget: StepBudget;
  /** The free-heap gauge of this world's module, shared with every world on it (see heap-gauge.ts). */
  private readonly heapGauge: HeapGauge;
  /** Stable ids of linear-cast (CCD) bodies: each takes step memory (see world-limits.ts). */
  private readonly ccdIds = new Set<number>();
  private readonly sensors: SensorHub;
  private nextBodyId = 1;
  private rays: RayQueries | null = null;
  private destroyed = false;
  private readonly stateReader: BodyStateReader;
  private readonly disposers = new Set<() => void>();
  private readonly internals: WorldInternals;

  static {
    internalsOf = (world) => world.internals;
  }

  private constructor(J: J, limits: WorldLimits, gravity: Vec3Like) {
    this.jolt = J;
    this.maxBodies = limits.maxBodies;
    this.minFreeHeapBytes = limits.minFreeHeapBytes;
    this.stepBudget = new StepBudget(limits);
    this.heapGauge = heapGaugeOf(J);
    const settings = new J.JoltSettings(); // freed once JoltInterface has copied it
    settings.mMaxBodies = limits.maxBodies;
    settings.mMaxBodyPairs = limits.maxBodyPairs;
    settings.mMaxContactConstraints = limits.maxContactConstraints;
    this.filters = createLayerFilters(J);
    settings.mObjectLayerPairFilter = this.filters.objectLayerPairFilter; // JoltInterface takes ownership
    settings.mBroadPhaseLayerInterface = this.filters.broadPhaseLayerInterface; // JoltInterface takes ownership
    settings.mObjectVsBroadPhaseLayerFilter = this.filters.objectVsBroadPhaseLayerFilter; // JoltInterface takes ownership
    this.joltInterface = new J.JoltInterface(settings); // owned by this world; destroyed in destroy()
    J.destroy(settings);
    this.system = this.joltInterface.GetPhysicsSystem();
    this.bodyInterface = this.system.GetBodyInterface();
    this.constraints = new ConstraintRegistry(J, this.system);
    this.slots = new BodySlots(J, this.bodyInterface, this.maxBodies); // owned here; disposed in destroy()
    this.stateReader = new BodyStateReader(J, this.system);
    this.sensors = new SensorHub(J, this.system, {
      stableIdOf: (joltId) => this.table.byJoltId(joltId)?.id,
      isSensorJoltId: (joltId) => this.table.isSensorJoltId(joltId),
      isStaticJoltId: (joltId) => this.table.byJoltId(joltId)?.motion === 'static',
    });
    this.internals = {
      slots: this.slots,
      disposers: this.disposers,
      sensorHub: this.sensors,
      track: (body, info, id) => this.track(body, info, id),
      untrack: (handle) => this.untrack(handle),
      bodyByJoltId: (joltId) => this.table.byJoltId(joltId),
      setNextBodyId: (next) => void (this.nextBodyId = next),
      setEveryBodyReads: (every) => void (this.stateReader.everyBody = every),
      gravity: { x: 0, y: 0, z: 0, vec: new J.Vec3(0, 0, 0) }, // the Vec3 is owned by this world; destroyed in destroy()
      tempAllocator: this.joltInterface.GetTempAllocator(),
    };
    this.setGravity(gravity.x, gravity.y, gravity.z);
  }

  /**
   * Loads Jolt (memoized) and builds a world. Throws a clear Error for bad limits, limits whose step could overflow
   * Jolt's fixed temp allocator, or a heap too full for another world (~15 MB each at the defaults).
   */
  static async create(opts: PhysicsWorldOptions = {}): Promise<PhysicsWorld> {
    const limits = resolveWorldLimits(opts);
    const gravity = opts.gravity ?? { x: 0, y: -9.81, z: 0 };
    checkVec3(gravity, 'PhysicsWorld.create', 'gravity');
    const J = opts.jolt ?? (opts.isolatedModule ? await createJoltInstance(opts) : await loadJolt(opts));
    ensureRoomForWorld(heapGaugeOf(J).read(), limits);
    const world = new PhysicsWorld(J, limits, gravity);
    heapGaugeOf(J).read(); // the new world took heap the gauge never granted
    return world;
  }

  private live(): void {
    if (this.destroyed) throw new Error('PhysicsWorld was destroyed');
  }

  /** Sets gravity (m/s²). */
  setGravity(x: number, y: number, z: number): void {
    this.live();
    checkVec3({ x, y, z }, 'setGravity', 'gravity');
    const g = this.internals.gravity;
    g.vec.Set(x, y, z);
    this.system.SetGravity(g.vec);
    g.x = g.vec.GetX(); // float32, as Jolt holds it
    g.y = g.vec.GetY();
    g.z = g.vec.GetZ();
  }

  /** Variable step (seed §25.8): clamps to 1/30 s, two collision sub-steps above 1/55 s. */
  step(dtSeconds: number): SensorEvent[] {
    this.live();
    if (!Number.isFinite(dtSeconds) || dtSeconds <= 0) throw new Error(`step: dtSeconds must be a finite number > 0, got ${dtSeconds}`);
    const dt = Math.min(dtSeconds, MAX_STEP_SECONDS);
    const steps = dt > SUBSTEP_THRESHOLD_SECONDS ? 2 : 1;
    this.joltInterface.Step(dt, steps);
    this.stateReader.stepped();
    return this.deliverSensorEvents();
  }

  /** The server's fixed tick: exactly TICK_DT_SECONDS (1/60 s) with one collision step. */
  stepFixed(): SensorEvent[] {
    this.live();
    this.joltInterface.Step(TICK_DT_SECONDS, 1);
    this.stateReader.stepped();
    return this.deliverSensorEvents();
  }

  /**
   * Runs the sensor callbacks in event order. A callback that throws does not stop the others: every callback runs,
   * then the first error is rethrown (the tick's events are lost to the caller, as with any throwing step).
   */
  private deliverSensorEvents(): SensorEvent[] {
    const events = this.sensors.drain();
    let failure: { error: unknown; event: SensorEvent } | undefined;
    for (const e of events) {
      const sensor = this.table.get(e.sensorId);
      const cb = e.kind === 'enter' ? sensor?.sensor?.onEnter : sensor?.sensor?.onExit;
      if (!cb) continue;
      try {
        cb(this.table.get(e.otherId));
      } catch (error) {
        failure ??= { error, event: e };
      }
    }
    if (failure) {
      const { error, event } = failure;
      const detail = error instanceof Error ? error.message : String(error);
      throw new Error(`sensor ${event.sensorId}: its on${event.kind === 'enter' ? 'Enter' : 'Exit'} callback for body ${event.otherId} threw: ${detail}`, { cause: error });
    }
    return events;
  }

  // ── factories ──────────────────────────────────────────────────────────────────────────────────────────────

  /** A box with half extents `half` (m). */
  addBox(half: Vec3Like, pos: Vec3Like, rot: QuatLike | null = null, opts: BodyOptions = {}): BodyHandle {
    return this.addShape({ kind: 'box', halfExtents: { x: half.x, y: half.y, z: half.z } }, pos, rot, opts);
  }

  /** A sphere of `radius` (m). */
  addSphere(radius: number, pos: Vec3Like, opts: BodyOptions = {}): BodyHandle {
    return this.addShape({ kind: 'sphere', radius }, pos, null, opts);
  }

  /** A Y-axis capsule: cylinder half-length `halfHeight` plus hemispheres of `radius`. */
  addCapsule(halfHeight: number, radius: number, pos: Vec3Like, rot: QuatLike | null = null, opts: BodyOptions = {}): BodyHandle {
    return this.addShape({ kind: 'capsule', halfHeight, radius }, pos, rot, opts);
  }

  /** A Y-axis cylinder. */
  addCylinder(halfHeight: number, radius: number, pos: Vec3Like, rot: QuatLike | null = null, opts: BodyOptions = {}): BodyHandle {
    return this.addShape({ kind: 'cylinder', halfHeight, radius }, pos, rot, opts);
  }

  /** The convex hull of a point cloud (flat x,y,z array or a list of points). */
  addConvexHull(points: ArrayLike<number> | Vec3Like[], pos: Vec3Like, rot: QuatLike | null = null, opts: BodyOptions = {}): BodyHandle {
    return this.addShape({ kind: 'convexHull', points: flattenPoints(points) }, pos, rot, opts);
  }

  /** A triangle soup (static or kinematic only). */
  addMeshCollider(positions: ArrayLike<number>, indices: ArrayLike<number>, pos: Vec3Like, rot: QuatLike | null = null, opts: BodyOptions = {}): BodyHandle {
    return this.addShape({ kind: 'mesh', positions, indices }, pos, rot, { ...opts, motion: opts.motion ?? 'static' });
  }

  /** A sampleCount × sampleCount height grid; sample (x, z) sits at originXz + (x, z)·cellSize (static only). */
  addHeightField(heights: ArrayLike<number>, sampleCount: number, cellSize: number, originXz: { x: number; z: number } = { x: 0, z: 0 }, opts: BodyOptions = {}): BodyHandle {
    const spec: ShapeSpec = { kind: 'heightField', heights, sampleCount, cellSize, originXz };
    return this.addShape(spec, { x: 0, y: 0, z: 0 }, null, { ...opts, motion: opts.motion ?? 'static' });
  }

  /** A compound of convex parts placed relative to the body. */
  addCompound(parts: Extract<ShapeSpec, { kind: 'compound' }>['parts'], pos: Vec3Like, rot: QuatLike | null = null, opts: BodyOptions = {}): BodyHandle {
    return this.addShape({ kind: 'compound', parts }, pos, rot, opts);
  }

  /**
   * Builds any described shape into a body: the generic factory behind the named ones. `at` (checkpoint restore
   * only) recreates a body under a given stable id and Jolt BodyID.
   */
  addShape(spec: ShapeSpec, pos: Vec3Like, rot: QuatLike | null = null, opts: BodyOptions = {}, at?: { id: number; joltId: number }): BodyHandle {
    this.live();
    if (at && this.table.get(at.id)) throw new Error(`addShape: stable id ${at.id} is already in use`);
    const what = `${spec?.kind ?? 'shape'}${opts.name ? ` "${opts.name}"` : ''}`;
    const motion = resolveMotion(opts);
    if (spec && STATIC_ONLY_KINDS.has(spec.kind) && motion === 'dynamic') {
      throw new Error(`${what}: a ${spec.kind} has no volume or inertia, so it can only be static or kinematic`);
    }
    if (spec?.kind === 'heightField' && motion !== 'static') throw new Error(`${what}: a height field can only be static`);
    checkVec3(pos, what, 'position');
    if (rot) checkQuat(rot, what, 'rotation');
    const { layer, mask } = resolveLayerMask(opts, motion, what);
    validateBodyOptions(opts, what);
    validateShapeSpec(spec, what);
    this.ensureRoom(estimateShapeBytes(spec) + 2048, what);
    const ccd = opts.motionQuality === 'linearCast' && motion !== 'static';
    if (ccd) this.stepBudget.reserve('ccdBody', what);
    let handle: BodyHandle | undefined;
    try {
      const shape = buildValidatedShape(this.jolt, spec, what);
      try {
        handle = this.createBody(shape, spec, pos, rot ?? IDENTITY_QUAT, motion, layer, mask, opts, what, at);
      } finally {
        shape.Release(); // the body holds its own reference now (or creation failed and this frees the shape)
      }
    } finally {
      if (ccd && !handle) this.stepBudget.release('ccdBody');
    }
    if (ccd) this.ccdIds.add(handle.id);
    return handle;
  }

  /** Throws a clear Error when the world is full or the heap cannot take `bytes` more. */
  ensureRoom(bytes: number, what: string): void {
    this.live();
    if (this.table.size >= this.maxBodies) {
      throw new Error(`${what}: the world is full (${this.maxBodies} bodies, the maxBodies limit of PhysicsWorld.create)`);
    }
    ensureHeapRoom(this.heapGauge.freeBytesFor(bytes, this.minFreeHeapBytes), bytes, this.minFreeHeapBytes, what);
    this.heapGauge.grant(bytes);
  }

  /** Heap bytes a full state save (SaveState with contacts) of this world may take at its peak. */
  stateSaveHeapBytes(): number {
    return estimateStateSaveBytes(this.table.size, this.constraints.size);
  }

  /** Throws a clear Error unless the heap can take a full state save and still keep the reserve. */
  ensureRoomForStateSave(what: string): void {
    this.live();
    const bytes = this.stateSaveHeapBytes();
    ensureHeapRoom(this.heapGauge.freeBytesFor(bytes, this.minFreeHeapBytes), bytes, this.minFreeHeapBytes, what);
    this.heapGauge.grant(bytes);
  }

  /**
   * How many more linear-cast (CCD) bodies or constraints the step budget takes before factories refuse them
   * (lets a caller drop a shot deterministically instead of catching the Error).
   */
  stepBudgetRoom(kind: 'ccdBody' | 'constraint'): number {
    this.live();
    return this.stepBudget.room(kind);
  }

  /** Free bytes in Jolt's fixed 128 MiB heap (an exact reading: it walks the allocator). */
  freeHeapBytes(): number {
    return this.heapGauge.read();
  }

  /** Size of the world's WASM heap in bytes (fixed: 128 MiB); shared with other worlds on the same module. */
  totalHeapBytes(): number {
    return this.jolt.JoltInterface.prototype.sGetTotalMemory();
  }

  private createBody(shape: JoltShape, spec: ShapeSpec, pos: Vec3Like, rot: QuatLike, motion: MotionKind, layer: number, mask: number, opts: BodyOptions, what: string, at?: { id: number; joltId: number }): BodyHandle {
    const J = this.jolt;
    const isSensor = opts.isSensor === true || opts.sensor !== undefined;
    const { settings, joltMotion } = makeCreationSettings(J, shape, pos, rot, motion, layer, mask, opts, isSensor); // freed below
    if (opts.noCollideGroup !== undefined) this.slots.applyNoCollideGroup(settings, opts.noCollideGroup);
    let body: JoltBody;
    try {
      body = this.slots.create(settings, at?.joltId); // at the deterministic BodyID (see body-slots.ts)
    } catch (err) {
      throw new Error(`${what}: ${(err as Error).message} (the world holds ${this.table.size} of maxBodies ${this.maxBodies})`);
    } finally {
      J.destroy(settings);
    }
    this.bodyInterface.AddBody(body.GetID(), joltMotion === 'static' ? J.EActivation_DontActivate : J.EActivation_Activate);
    const handle = this.track(body, { motion, layer, mask, isSensor, role: 'body', shape: spec, opts }, at?.id);
    if (isSensor) this.sensors.ensureInstalled();
    return handle;
  }

  private track(body: JoltBody, info: TrackInfo, id: number = this.nextBodyId++): BodyHandle {
    const joltId = body.GetID().GetIndexAndSequenceNumber();
    const handle = new BodyHandle({
      J: this.jolt,
      id,
      raw: body,
      joltId,
      motion: info.motion,
      layer: info.layer,
      mask: info.mask,
      isSensor: info.isSensor,
      role: info.role,
      shape: info.shape,
      name: info.opts.name,
      userData: info.opts.userData,
      sensor: info.opts.sensor,
    });
    this.table.add(handle);
    this.stateReader.add(handle);
    return handle;
  }

  private untrack(handle: BodyHandle): void {
    this.sensors.forgetBody(handle.joltId);
    this.slots.release(handle.joltId);
    this.table.delete(handle);
    this.stateReader.remove(handle);
    if (this.ccdIds.delete(handle.id)) this.stepBudget.release('ccdBody');
    handle.removed = true;
  }

  /** Removes and destroys a body (and any constraint attached to it). Its sensor overlaps close with exit events. */
  removeBody(handleOrId: BodyHandle | number): void {
    this.live();
    const handle = typeof handleOrId === 'number' ? this.table.get(handleOrId) : handleOrId;
    if (!this.table.owns(handle)) {
      throw new Error(`removeBody: no body ${typeof handleOrId === 'number' ? handleOrId : handleOrId.id} in this world`);
    }
    if (handle.role === 'character') throw new Error(`removeBody: body ${handle.id} belongs to a CharacterController; destroy the controller`);
    this.releaseConstraints(this.constraints.removeFor(handle.id));
    const id = handle.raw.GetID();
    this.bodyInterface.RemoveBody(id);
    this.bodyInterface.DestroyBody(id);
    this.untrack(handle);
  }

  /** Removes every body and constraint (characters must be destroyed by their owners first). */
  clear(): void {
    this.live();
    this.releaseConstraints(this.constraints.clear());
    for (const id of [...this.table.sortedIds].reverse()) {
      const h = this.table.get(id)!;
      if (h.role !== 'character') this.removeBody(h);
    }
    this.sensors.drain();
  }

  /** Frees everything: bodies, constraints, helpers, the listener and the JoltInterface. */
  destroy(): void {
    if (this.destroyed) return;
    for (const dispose of [...this.disposers]) dispose();
    this.disposers.clear();
    this.clear();
    this.destroyed = true;
    this.slots.dispose();
    this.stateReader.dispose(this.system);
    this.jolt.destroy(this.joltInterface);
    this.jolt.destroy(this.internals.gravity.vec);
    this.sensors.dispose();
  }

  /** Whether destroy() has run. */
  get isDestroyed(): boolean {
    return this.destroyed;
  }

  /** Number of tracked bodies (including characters' inner bodies). */
  get bodyCount(): number {
    return this.table.size;
  }

  /** The handle for a stable id, or undefined. */
  getBody(id: number): BodyHandle | undefined {
    return this.table.get(id);
  }

  /** Stable ids of every tracked body, ascending (a copy). */
  bodyIds(): number[] {
    return this.table.sortedIds.slice();
  }

  /** The id the next body will get (checkpoints save it and restore it through WorldInternals.setNextBodyId). */
  get nextId(): number {
    return this.nextBodyId;
  }

  /** Stable ids of bodies currently overlapping a sensor, ascending. */
  sensorOverlaps(sensor: BodyHandle | number): number[] {
    return this.sensors.overlapping(typeof sensor === 'number' ? sensor : sensor.id);
  }

  // ── motion control ────────────────────────────────────────────────────────────────────────────────────────

  private handleOf(b: BodyHandle | number, what: string): BodyHandle {
    this.live();
    const h = typeof b === 'number' ? this.table.get(b) : b;
    if (!this.table.owns(h)) throw new Error(`${what}: no body ${typeof b === 'number' ? b : b.id} in this world`);
    return h;
  }

  /** Sets a body's linear velocity (m/s) and wakes it (not for static bodies). */
  setLinearVelocity(b: BodyHandle | number, v: Vec3Like): void {
    const h = this.handleOf(b, 'setLinearVelocity');
    motion.setLinearVelocity(this, h, v);
    this.stateReader.touch(h);
  }

  /** Sets a body's angular velocity (rad/s) and wakes it (not for static bodies). */
  setAngularVelocity(b: BodyHandle | number, v: Vec3Like): void {
    const h = this.handleOf(b, 'setAngularVelocity');
    motion.setAngularVelocity(this, h, v);
    this.stateReader.touch(h);
  }

  /** Applies an impulse (N·s) to a dynamic body at its centre of mass, or at a world point, and wakes it. */
  addImpulse(b: BodyHandle | number, impulse: Vec3Like, worldPoint?: Vec3Like): void {
    const h = this.handleOf(b, 'addImpulse');
    motion.addImpulse(this, h, impulse, worldPoint);
    this.stateReader.touch(h);
  }

  /** Moves a kinematic body so it reaches pos/rot after dtSeconds (velocity-based: pushes dynamics). */
  moveKinematic(b: BodyHandle | number, pos: Vec3Like, rot: QuatLike | null, dtSeconds: number = TICK_DT_SECONDS): void {
    const h = this.handleOf(b, 'moveKinematic');
    motion.moveKinematic(this, h, pos, rot, dtSeconds);
    this.stateReader.touch(h);
  }

  /** Teleports a body (no velocity change); activates it unless static. */
  setPosition(b: BodyHandle | number, pos: Vec3Like, rot: QuatLike | null = null): void {
    const h = this.handleOf(b, 'setPosition');
    motion.setPosition(this, h, pos, rot);
    this.stateReader.touch(h);
  }

  // ── queries ───────────────────────────────────────────────────────────────────────────────────────────────

  private queries(): RayQueries {
    this.live();
    if (!this.rays) {
      const rays = new RayQueries(this, (joltId) => this.table.byJoltId(joltId));
      this.rays = rays;
      this.disposers.add(() => {
        rays.dispose();
        this.rays = null;
      });
    }
    return this.rays;
  }

  /** Closest hit along origin + t·direction, t in [0, 1] (|direction| is the reach); null if none. */
  rayCast(origin: Vec3Like, direction: Vec3Like, staticOnly = false): RayHit | null {
    return this.queries().rayCast(origin, direction, staticOnly);
  }

  /** Height of the first surface below (x, y, z) within dist metres, or null; allocates nothing. */
  rayDownY(x: number, y: number, z: number, dist: number, staticOnly = false): number | null {
    return this.queries().rayDownY(x, y, z, dist, staticOnly);
  }

  /** Jolt's temp allocator (character updates need it). */
  get tempAllocator(): InstanceType<J['TempAllocator']> {
    return this.internals.tempAllocator;
  }

  /**
   * Reads every tracked body, in stable-id order, into reused typed arrays: `states` holds BODY_STATE_STRIDE
   * floats per body (position, rotation, linear and angular velocity), `flags` BodyFlag bits. The arrays are
   * overwritten by the next call: copy what you keep.
   */
  readBodyStates(): BodyStates {
    this.live();
    return this.stateReader.read(this.table.sortedIds, this.table.byId);
  }

  /** Ids (ascending) of awake non-static bodies outside the box [min, max] or with a non-finite position. */
  awakeBodiesOutside(min: Vec3Like, max: Vec3Like): number[] {
    this.live();
    return this.stateReader.awakeOutside(this.table.sortedIds, this.table.byId, min, max);
  }

  // ── constraints ───────────────────────────────────────────────────────────────────────────────────────────

  /**
   * Creates a constraint from any TwoBodyConstraintSettings between two different bodies of this world, at least one
   * of them dynamic. Always consumes (destroys) the settings, also when it throws.
   */
  addConstraint(settings: InstanceType<J['TwoBodyConstraintSettings']>, a: BodyHandle, b: BodyHandle): InstanceType<J['Constraint']> {
    try {
      this.live();
      if (!this.table.owns(a) || !this.table.owns(b)) throw new Error('addConstraint: both bodies must be live bodies of this world');
      if (a === b) throw new Error(`addConstraint: a constraint joins two different bodies, got body ${a.id} twice`);
      if (a.motion !== 'dynamic' && b.motion !== 'dynamic') {
        throw new Error(`addConstraint: bodies ${a.id} (${a.motion}) and ${b.id} (${b.motion}) cannot move; at least one must be dynamic`);
      }
      ensureHeapRoom(this.freeHeapBytes(), CONSTRAINT_HEAP_BYTES, this.minFreeHeapBytes, 'addConstraint');
      this.stepBudget.reserve('constraint', 'addConstraint');
    } catch (err) {
      this.jolt.destroy(settings);
      throw err;
    }
    return this.constraints.add(settings, a, b);
  }

  /** Removes a constraint created by addConstraint (or a link helper). */
  removeConstraint(constraint: InstanceType<J['Constraint']>): void {
    this.live();
    if (!this.constraints.remove(constraint)) throw new Error('removeConstraint: not a constraint of this world');
    this.releaseConstraints(1);
  }

  private releaseConstraints(count: number): void {
    for (let i = 0; i < count; i++) this.stepBudget.release('constraint');
  }

  /** Pins worldPivot on a to the same point on b (ball-and-socket). */
  pointLink(a: BodyHandle, b: BodyHandle, worldPivot: Vec3Like): InstanceType<J['Constraint']> {
    return pointLink(this, a, b, worldPivot);
  }

  /** Number of live constraints. */
  get constraintCount(): number {
    return this.constraints.size;
  }
}
