// Reads of a moving Jolt Body's rotation, velocities and (for shapes centred on their origin) position straight from
// the WASM heap, without the glue getters' four calls per body. The offsets are those of this jolt-physics build's
// Body and MotionProperties (wasm32, single precision); they are checked against the getters on the first bodies a
// module reads, and one mismatch sends that module's reads back to the getters for good.
import type { JoltModule } from './jolt-backend.ts';

/** Word (4-byte) offsets inside a Body: mPosition (centre of mass, Vec3), mRotation (Quat), mMotionProperties. */
export const BODY_COM_POSITION_WORD = 0;
export const BODY_ROTATION_WORD = 4;
export const BODY_MOTION_PROPERTIES_WORD = 17;
/** Word offsets inside MotionProperties: mLinearVelocity and mAngularVelocity (Vec3 each). */
export const MOTION_LINEAR_VELOCITY_WORD = 0;
export const MOTION_ANGULAR_VELOCITY_WORD = 4;
/** Non-static bodies compared with the getters (at their first read) before a module's offsets are trusted. */
const BODIES_TO_CHECK = 256;

type RawCall = (ptr: number) => number;

/** How one body slot is read: through the getters, or direct with the position from the getter, or all direct. */
export const BodyReadMode = { Getters: 0, DirectPoseFromGetter: 1, Direct: 2 } as const;

function rawCall(J: JoltModule, name: string): RawCall | undefined {
  const f: unknown = Reflect.get(J, name);
  return typeof f === 'function' ? (f as RawCall) : undefined;
}

/**
 * A module's direct-read state. `enabled` stays true only while every checked body read the same words both ways.
 * Body::GetPosition() is mPosition − mRotation·(centre of mass); with the centre of mass at the shape's origin the
 * product is ±0 for a finite rotation, so the position is mPosition bit for bit wherever each coordinate is finite
 * and non-zero (x − ±0 = x); the reader takes the getter otherwise.
 */
export class BodyMemory {
  private readonly J: JoltModule;
  private readonly getComPosition: RawCall;
  private readonly getRotation: RawCall;
  private readonly getLinear: RawCall;
  private readonly getAngular: RawCall;
  private readonly getMotionProperties: RawCall;
  private readonly getShape: RawCall;
  private readonly getShapeCom: RawCall;
  private checked = 0;
  enabled = true;

  private constructor(J: JoltModule, calls: RawCall[]) {
    this.J = J;
    [, this.getComPosition, this.getRotation, this.getLinear, this.getAngular, this.getMotionProperties, this.getShape, this.getShapeCom] = calls;
  }

  /** The module's direct-read state, or null when its build lacks a getter the check needs. */
  static of(J: JoltModule): BodyMemory | null {
    let m = memories.get(J);
    if (m === undefined) {
      const names = ['Body_GetPosition_0', 'Body_GetCenterOfMassPosition_0', 'Body_GetRotation_0', 'Body_GetLinearVelocity_0', 'Body_GetAngularVelocity_0', 'Body_GetMotionProperties_0', 'Body_GetShape_0', 'Shape_GetCenterOfMass_0'];
      const calls = names.map((n) => rawCall(J, `_emscripten_bind_${n}`));
      m = calls.every((c) => c !== undefined) ? new BodyMemory(J, calls as RawCall[]) : null;
      memories.set(J, m);
    }
    return m;
  }

  /** How to read a non-static body from now on (checks the offsets on it while the module is being checked). */
  modeFor(bodyPtr: number): number {
    if (this.enabled && this.checked < BODIES_TO_CHECK) this.check(bodyPtr);
    if (!this.enabled) return BodyReadMode.Getters;
    const com = this.getShapeCom(this.getShape(bodyPtr)) >> 2;
    const f = this.J.HEAPF32;
    return f[com] === 0 && f[com + 1] === 0 && f[com + 2] === 0 ? BodyReadMode.Direct : BodyReadMode.DirectPoseFromGetter;
  }

  private check(bodyPtr: number): void {
    this.checked++;
    const u = this.J.HEAPU32;
    const b = bodyPtr >> 2;
    const motion = u[b + BODY_MOTION_PROPERTIES_WORD];
    const same = (ptr: number, at: number, words: number): boolean => {
      const p = ptr >> 2;
      for (let k = 0; k < words; k++) if (u[p + k] !== u[at + k]) return false;
      return true;
    };
    const ok =
      motion === this.getMotionProperties(bodyPtr) &&
      motion !== 0 &&
      same(this.getComPosition(bodyPtr), b + BODY_COM_POSITION_WORD, 3) &&
      same(this.getRotation(bodyPtr), b + BODY_ROTATION_WORD, 4) &&
      same(this.getLinear(bodyPtr), (motion >> 2) + MOTION_LINEAR_VELOCITY_WORD, 3) &&
      same(this.getAngular(bodyPtr), (motion >> 2) + MOTION_ANGULAR_VELOCITY_WORD, 3);
    if (!ok) this.enabled = false;
  }
}

const memories = new WeakMap<JoltModule, BodyMemory | null>();
