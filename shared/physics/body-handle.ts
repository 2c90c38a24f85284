// BodyHandle: the caller's view of one body — a stable id, the raw Jolt Body, and plain-copy getters.
// The world owns the Jolt body; a handle is only valid until the body is removed (then `removed` is true).
import type { ShapeSpec } from '../physics-data/shape-spec.ts';
import type { QuatLike, Vec3Like } from '../physics-data/vectors.ts';
import type { JoltModule } from './jolt-backend.ts';
import type { MotionKind, SensorCallbacks } from './types.ts';

export type JoltBody = InstanceType<JoltModule['Body']>;

/** What a body is, for snapshot/render code: a plain body or a character's inner capsule. */
export type BodyRole = 'body' | 'character';

/** One tracked body. Getters return fresh plain objects (copies out of the WASM heap). */
export class BodyHandle<Other = unknown> {
  /** Stable id: the same in every run given the same creation order. */
  readonly id: number;
  /** The Jolt body (owned by the world; do not destroy). */
  readonly raw: JoltBody;
  /** Jolt's BodyID index+sequence number, the key contact callbacks use. */
  readonly joltId: number;
  readonly motion: MotionKind;
  readonly layer: number;
  readonly mask: number;
  readonly isSensor: boolean;
  readonly role: BodyRole;
  /** The shape this body was built from (undefined for character capsules built by Jolt). */
  readonly shape: ShapeSpec | undefined;
  readonly name: string | undefined;
  userData: unknown;
  /** Sensor callbacks when the body is a sensor. */
  readonly sensor: SensorCallbacks<Other> | undefined;
  /** Set once the world has removed the body; every accessor then throws. */
  removed = false;
  private readonly J: JoltModule;

  constructor(init: {
    J: JoltModule;
    id: number;
    raw: JoltBody;
    joltId: number;
    motion: MotionKind;
    layer: number;
    mask: number;
    isSensor: boolean;
    role: BodyRole;
    shape: ShapeSpec | undefined;
    name: string | undefined;
    userData: unknown;
    sensor: SensorCallbacks<Other> | undefined;
  }) {
    this.J = init.J;
    this.id = init.id;
    this.raw = init.raw;
    this.joltId = init.joltId;
    this.motion = init.motion;
    this.layer = init.layer;
    this.mask = init.mask;
    this.isSensor = init.isSensor;
    this.role = init.role;
    this.shape = init.shape;
    this.name = init.name;
    this.userData = init.userData;
    this.sensor = init.sensor;
  }

  private live(): JoltBody {
    if (this.removed) throw new Error(`body ${this.id}${this.name ? ` (${this.name})` : ''} was removed`);
    return this.raw;
  }

  /** World position (m) of the body's origin. */
  position(): Vec3Like {
    const p = this.live().GetPosition(); // a reused temporary: copy out at once
    return { x: p.GetX(), y: p.GetY(), z: p.GetZ() };
  }

  /** World rotation as a unit quaternion. */
  rotation(): QuatLike {
    const q = this.live().GetRotation(); // a reused temporary
    return { x: q.GetX(), y: q.GetY(), z: q.GetZ(), w: q.GetW() };
  }

  /** Linear velocity (m/s). */
  linearVelocity(): Vec3Like {
    const v = this.live().GetLinearVelocity();
    return { x: v.GetX(), y: v.GetY(), z: v.GetZ() };
  }

  /** Angular velocity (rad/s). */
  angularVelocity(): Vec3Like {
    const v = this.live().GetAngularVelocity();
    return { x: v.GetX(), y: v.GetY(), z: v.GetZ() };
  }

  /** Whether Jolt is simulating the body this step (false: asleep or static). */
  isActive(): boolean {
    return this.live().IsActive();
  }

  /** Reads pos(3) rot(4) linVel(3) angVel(3) into out at offset through HEAPF32 (no per-body allocation). */
  readStateInto(out: Float32Array, offset: number): void {
    const body = this.live();
    const J = this.J;
    const heap = J.HEAPF32;
    let p = J.getPointer(body.GetPosition()) >> 2;
    out[offset] = heap[p];
    out[offset + 1] = heap[p + 1];
    out[offset + 2] = heap[p + 2];
    p = J.getPointer(body.GetRotation()) >> 2;
    out[offset + 3] = heap[p];
    out[offset + 4] = heap[p + 1];
    out[offset + 5] = heap[p + 2];
    out[offset + 6] = heap[p + 3];
    p = J.getPointer(body.GetLinearVelocity()) >> 2;
    out[offset + 7] = heap[p];
    out[offset + 8] = heap[p + 1];
    out[offset + 9] = heap[p + 2];
    p = J.getPointer(body.GetAngularVelocity()) >> 2;
    out[offset + 10] = heap[p];
    out[offset + 11] = heap[p + 1];
    out[offset + 12] = heap[p + 2];
  }
}
