// BodyOptions handling: resolving motion, validating every tunable, and copying them into Jolt BodyCreationSettings.
import { checkVec3 } from '../physics-data/shape-spec.ts';
import type { QuatLike, Vec3Like } from '../physics-data/vectors.ts';
import type { JoltModule } from './jolt-backend.ts';
import { checkNoCollideGroup } from './body-slots.ts';
import { assertGroupBits, CollisionLayer, packObjectLayer } from './layers.ts';
import type { JoltShape } from './shapes.ts';
import type { BodyOptions, MotionKind } from './types.ts';

type J = JoltModule;

/** A body's groups: `opts.layer`/`mask`, or the defaults (Trigger for sensors, World for statics, else Prop; mask All). */
export function resolveLayerMask(opts: BodyOptions, motion: MotionKind, what: string): { layer: number; mask: number } {
  const sensor = opts.isSensor === true || opts.sensor !== undefined;
  const layer = opts.layer ?? (sensor ? CollisionLayer.Trigger : motion === 'static' ? CollisionLayer.World : CollisionLayer.Prop);
  const mask = opts.mask ?? CollisionLayer.All;
  assertGroupBits(layer, `${what}: layer`);
  assertGroupBits(mask, `${what}: mask`);
  return { layer, mask };
}

/**
 * A BodyCreationSettings for a validated body (the caller destroys it) and the motion type Jolt gets. A static
 * Jolt sensor loses every body that falls asleep inside it (a spurious exit); Jolt keeps an active kinematic sensor
 * awake and lets it see sleeping bodies, so a 'static' sensor becomes a kinematic one that never moves.
 */
export function makeCreationSettings(J: J, shape: JoltShape, pos: Vec3Like, rot: QuatLike, motion: MotionKind, layer: number, mask: number, opts: BodyOptions, isSensor: boolean): { settings: InstanceType<J['BodyCreationSettings']>; joltMotion: MotionKind } {
  const joltMotion: MotionKind = isSensor && motion === 'static' ? 'kinematic' : motion;
  const motionType = joltMotion === 'static' ? J.EMotionType_Static : joltMotion === 'kinematic' ? J.EMotionType_Kinematic : J.EMotionType_Dynamic;
  const rPos = new J.RVec3(pos.x, pos.y, pos.z); // copied into the settings, freed below
  const qRot = new J.Quat(rot.x, rot.y, rot.z, rot.w); // copied into the settings, freed below
  const settings = new J.BodyCreationSettings(shape, rPos, qRot, motionType, packObjectLayer(J, layer, mask)); // the caller destroys it
  J.destroy(rPos);
  J.destroy(qRot);
  applyBodyOptions(J, settings, opts, motion, isSensor);
  return { settings, joltMotion };
}

/** Copies the tunables of `opts` into a BodyCreationSettings (restitution defaults to 0.2). */
export function applyBodyOptions(J: J, settings: InstanceType<J['BodyCreationSettings']>, opts: BodyOptions, motion: MotionKind, isSensor: boolean): void {
  settings.mRestitution = opts.restitution ?? 0.2;
  if (opts.friction !== undefined) settings.mFriction = opts.friction;
  if (opts.gravityFactor !== undefined) settings.mGravityFactor = opts.gravityFactor;
  if (opts.linearDamping !== undefined) settings.mLinearDamping = opts.linearDamping;
  if (opts.angularDamping !== undefined) settings.mAngularDamping = opts.angularDamping;
  if (opts.allowSleeping === false) settings.mAllowSleeping = false;
  settings.mMotionQuality = opts.motionQuality === 'linearCast' ? J.EMotionQuality_LinearCast : J.EMotionQuality_Discrete;
  if (opts.massKg !== undefined && motion !== 'static') {
    settings.mOverrideMassProperties = J.EOverrideMassProperties_CalculateInertia;
    settings.mMassPropertiesOverride.mMass = opts.massKg;
  }
  // Jolt 5.6 pairs a kinematic body with any sensor by itself, so no mCollideKinematicVsNonDynamic here: that flag
  // would make kinematic sensors report the static level geometry they overlap.
  if (isSensor) settings.mIsSensor = true;
  if (opts.linearVelocity) settings.mLinearVelocity.Set(opts.linearVelocity.x, opts.linearVelocity.y, opts.linearVelocity.z);
  if (opts.angularVelocity) settings.mAngularVelocity.Set(opts.angularVelocity.x, opts.angularVelocity.y, opts.angularVelocity.z);
}

/** The motion kind from `motion`, or the legacy `dynamic` flag. */
export function resolveMotion(opts: BodyOptions): MotionKind {
  if (opts.motion !== undefined) {
    if (opts.motion !== 'static' && opts.motion !== 'dynamic' && opts.motion !== 'kinematic') {
      throw new Error(`motion must be 'static', 'dynamic' or 'kinematic', got ${JSON.stringify(opts.motion)}`);
    }
    return opts.motion;
  }
  if (opts.dynamic === false) return 'static';
  return 'dynamic';
}

/** Throws a clear Error for any out-of-range or non-finite tunable. */
export function validateBodyOptions(opts: BodyOptions, what: string): void {
  const num = (v: number | undefined, field: string, min: number, max = Infinity): void => {
    if (v === undefined) return;
    if (typeof v !== 'number' || !Number.isFinite(v) || v < min || v > max) {
      throw new Error(`${what}: ${field} must be a finite number in [${min}, ${max}], got ${String(v)}`);
    }
  };
  num(opts.restitution, 'restitution', 0, 1);
  num(opts.friction, 'friction', 0);
  num(opts.gravityFactor, 'gravityFactor', -100, 100);
  num(opts.linearDamping, 'linearDamping', 0);
  num(opts.angularDamping, 'angularDamping', 0);
  if (opts.massKg !== undefined && (!Number.isFinite(opts.massKg) || opts.massKg <= 0)) {
    throw new Error(`${what}: massKg must be a finite number > 0, got ${String(opts.massKg)}`);
  }
  if (opts.linearVelocity) checkVec3(opts.linearVelocity, what, 'linearVelocity');
  if (opts.angularVelocity) checkVec3(opts.angularVelocity, what, 'angularVelocity');
  if (opts.noCollideGroup !== undefined) checkNoCollideGroup(opts.noCollideGroup, what);
  if (opts.motionQuality !== undefined && opts.motionQuality !== 'discrete' && opts.motionQuality !== 'linearCast') {
    throw new Error(`${what}: motionQuality must be 'discrete' or 'linearCast'`);
  }
}

/** Accepts a flat x,y,z array or a list of points. */
export function flattenPoints(points: ArrayLike<number> | Vec3Like[]): ArrayLike<number> {
  if (Array.isArray(points) && points.length > 0 && typeof points[0] === 'object') {
    const out = new Array<number>(points.length * 3);
    (points as Vec3Like[]).forEach((p, i) => {
      out[i * 3] = p?.x;
      out[i * 3 + 1] = p?.y;
      out[i * 3 + 2] = p?.z;
    });
    return out;
  }
  return points as ArrayLike<number>;
}
