// Motion control of live bodies: velocities, impulses, kinematic moves and teleports through Jolt's BodyInterface.
// Validates every input first and frees each Jolt temporary at once; PhysicsWorld's methods delegate here.
import { checkQuat, checkVec3 } from '../physics-data/shape-spec.ts';
import type { QuatLike, Vec3Like } from '../physics-data/vectors.ts';
import type { BodyHandle } from './body-handle.ts';
import type { JoltModule } from './jolt-backend.ts';

type J = JoltModule;

/** What motion control needs from the world. */
export interface MotionTarget {
  readonly jolt: J;
  readonly bodyInterface: InstanceType<J['BodyInterface']>;
}

/** Sets a body's linear velocity (m/s) and wakes it. */
export function setLinearVelocity(w: MotionTarget, h: BodyHandle, v: Vec3Like): void {
  checkVec3(v, 'setLinearVelocity', 'velocity');
  if (h.motion === 'static') throw new Error(`setLinearVelocity: body ${h.id} is static; static bodies never move`);
  const jv = new w.jolt.Vec3(v.x, v.y, v.z); // copied, freed at once
  w.bodyInterface.SetLinearVelocity(h.raw.GetID(), jv);
  w.jolt.destroy(jv);
}

/** Sets a body's angular velocity (rad/s) and wakes it. */
export function setAngularVelocity(w: MotionTarget, h: BodyHandle, v: Vec3Like): void {
  checkVec3(v, 'setAngularVelocity', 'velocity');
  if (h.motion === 'static') throw new Error(`setAngularVelocity: body ${h.id} is static; static bodies never move`);
  const jv = new w.jolt.Vec3(v.x, v.y, v.z); // copied, freed at once
  w.bodyInterface.SetAngularVelocity(h.raw.GetID(), jv);
  w.jolt.destroy(jv);
}

/** Applies an impulse (N·s) at the centre of mass, or at a world point, and wakes the body. */
export function addImpulse(w: MotionTarget, h: BodyHandle, impulse: Vec3Like, worldPoint?: Vec3Like): void {
  checkVec3(impulse, 'addImpulse', 'impulse');
  if (worldPoint) checkVec3(worldPoint, 'addImpulse', 'worldPoint');
  if (h.motion !== 'dynamic') throw new Error(`addImpulse: body ${h.id} is ${h.motion}; only dynamic bodies take impulses`);
  const J = w.jolt;
  const ji = new J.Vec3(impulse.x, impulse.y, impulse.z); // copied, freed below
  if (worldPoint) {
    const p = new J.RVec3(worldPoint.x, worldPoint.y, worldPoint.z); // copied, freed below
    w.bodyInterface.AddImpulse(h.raw.GetID(), ji, p);
    J.destroy(p);
  } else {
    w.bodyInterface.AddImpulse(h.raw.GetID(), ji);
  }
  J.destroy(ji);
}

/** Moves a kinematic body so it reaches pos/rot after dtSeconds (velocity-based: it pushes dynamic bodies). */
export function moveKinematic(w: MotionTarget, h: BodyHandle, pos: Vec3Like, rot: QuatLike | null, dtSeconds: number): void {
  if (h.motion !== 'kinematic') throw new Error(`moveKinematic: body ${h.id} is ${h.motion}, not kinematic`);
  checkVec3(pos, 'moveKinematic', 'position');
  const r = rot ?? h.rotation();
  checkQuat(r, 'moveKinematic', 'rotation');
  if (typeof dtSeconds !== 'number' || !Number.isFinite(dtSeconds) || dtSeconds <= 0) {
    throw new Error(`moveKinematic: dtSeconds must be a finite number > 0, got ${String(dtSeconds)}`);
  }
  const J = w.jolt;
  const p = new J.RVec3(pos.x, pos.y, pos.z); // copied, freed below
  const q = new J.Quat(r.x, r.y, r.z, r.w); // copied, freed below
  w.bodyInterface.MoveKinematic(h.raw.GetID(), p, q, dtSeconds);
  J.destroy(p);
  J.destroy(q);
}

/** Teleports a body (velocities kept); wakes it unless it is static. */
export function setPosition(w: MotionTarget, h: BodyHandle, pos: Vec3Like, rot: QuatLike | null): void {
  checkVec3(pos, 'setPosition', 'position');
  const r = rot ?? h.rotation();
  checkQuat(r, 'setPosition', 'rotation');
  const J = w.jolt;
  const p = new J.RVec3(pos.x, pos.y, pos.z); // copied, freed below
  const q = new J.Quat(r.x, r.y, r.z, r.w); // copied, freed below
  w.bodyInterface.SetPositionAndRotation(h.raw.GetID(), p, q, h.motion === 'static' ? J.EActivation_DontActivate : J.EActivation_Activate);
  J.destroy(p);
  J.destroy(q);
}
