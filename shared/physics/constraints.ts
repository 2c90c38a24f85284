// Constraints in world space: point (ball-and-socket), hinge, distance and slider helpers that build Jolt settings
// and hand them to PhysicsWorld.addConstraint, and the registry that owns each world's constraints until removal.
import { checkVec3 } from '../physics-data/shape-spec.ts';
import type { Vec3Like } from '../physics-data/vectors.ts';
import type { BodyHandle } from './body-handle.ts';
import type { JoltModule } from './jolt-backend.ts';
import type { PhysicsWorld } from './physics-world.ts';

type Constraint = InstanceType<JoltModule['Constraint']>;

/**
 * Position iterations the link helpers ask of Jolt (its default is 2): a 5-link chain released 60° from the vertical
 * then stretches at most 0.9% instead of 1.7%. Change one link with constraint.SetNumPositionStepsOverride(n).
 */
export const LINK_POSITION_STEPS = 6;

function normalized(v: Vec3Like, what: string, field: string): Vec3Like {
  checkVec3(v, what, field);
  const len = Math.sqrt(v.x * v.x + v.y * v.y + v.z * v.z);
  if (len < 1e-9) throw new Error(`${what}: ${field} must be a non-zero vector`);
  return { x: v.x / len, y: v.y / len, z: v.z / len };
}

/** Any unit vector perpendicular to `axis` (deterministic: arithmetic and sqrt only). */
function perpendicular(axis: Vec3Like): Vec3Like {
  const ref = Math.abs(axis.x) < 0.9 ? { x: 1, y: 0, z: 0 } : { x: 0, y: 1, z: 0 };
  const c = { x: axis.y * ref.z - axis.z * ref.y, y: axis.z * ref.x - axis.x * ref.z, z: axis.x * ref.y - axis.y * ref.x };
  const len = Math.sqrt(c.x * c.x + c.y * c.y + c.z * c.z);
  return { x: c.x / len, y: c.y / len, z: c.z / len };
}

/** Pins `worldPivot` on body a to the same point on body b; rotation stays free (seed §25.11). */
export function pointLink(world: PhysicsWorld, a: BodyHandle, b: BodyHandle, worldPivot: Vec3Like): Constraint {
  checkVec3(worldPivot, 'pointLink', 'worldPivot');
  const J = world.jolt;
  const settings = new J.PointConstraintSettings(); // consumed by addConstraint
  settings.mSpace = J.EConstraintSpace_WorldSpace;
  settings.mPoint1.Set(worldPivot.x, worldPivot.y, worldPivot.z);
  settings.mPoint2.Set(worldPivot.x, worldPivot.y, worldPivot.z);
  settings.mNumPositionStepsOverride = LINK_POSITION_STEPS;
  return world.addConstraint(settings, a, b);
}

/** A hinge about `axis` through `worldPivot`, optionally limited to [minRadians, maxRadians]. */
export function hingeLink(world: PhysicsWorld, a: BodyHandle, b: BodyHandle, worldPivot: Vec3Like, axis: Vec3Like, limits?: { minRadians: number; maxRadians: number }): Constraint {
  checkVec3(worldPivot, 'hingeLink', 'worldPivot');
  const h = normalized(axis, 'hingeLink', 'axis');
  const n = perpendicular(h);
  const J = world.jolt;
  const settings = new J.HingeConstraintSettings(); // consumed by addConstraint
  settings.mSpace = J.EConstraintSpace_WorldSpace;
  settings.mPoint1.Set(worldPivot.x, worldPivot.y, worldPivot.z);
  settings.mPoint2.Set(worldPivot.x, worldPivot.y, worldPivot.z);
  settings.mHingeAxis1.Set(h.x, h.y, h.z);
  settings.mHingeAxis2.Set(h.x, h.y, h.z);
  settings.mNormalAxis1.Set(n.x, n.y, n.z);
  settings.mNormalAxis2.Set(n.x, n.y, n.z);
  if (limits) {
    const { minRadians, maxRadians } = limits;
    if (!(minRadians <= 0 && maxRadians >= 0 && minRadians >= -Math.PI && maxRadians <= Math.PI)) {
      J.destroy(settings);
      throw new Error(`hingeLink: limits must satisfy -π <= min <= 0 <= max <= π, got [${minRadians}, ${maxRadians}]`);
    }
    settings.mLimitsMin = minRadians;
    settings.mLimitsMax = maxRadians;
  }
  settings.mNumPositionStepsOverride = LINK_POSITION_STEPS;
  return world.addConstraint(settings, a, b);
}

/** Keeps the distance between pointA (on a) and pointB (on b) within [minDistance, maxDistance] (default: current). */
export function distanceLink(world: PhysicsWorld, a: BodyHandle, b: BodyHandle, pointA: Vec3Like, pointB: Vec3Like, range?: { minDistance: number; maxDistance: number }): Constraint {
  checkVec3(pointA, 'distanceLink', 'pointA');
  checkVec3(pointB, 'distanceLink', 'pointB');
  const J = world.jolt;
  const settings = new J.DistanceConstraintSettings(); // consumed by addConstraint
  settings.mSpace = J.EConstraintSpace_WorldSpace;
  settings.mPoint1.Set(pointA.x, pointA.y, pointA.z);
  settings.mPoint2.Set(pointB.x, pointB.y, pointB.z);
  if (range) {
    if (!(range.minDistance >= 0 && range.maxDistance >= range.minDistance && Number.isFinite(range.maxDistance))) {
      J.destroy(settings);
      throw new Error(`distanceLink: need 0 <= minDistance <= maxDistance, got [${range.minDistance}, ${range.maxDistance}]`);
    }
    settings.mMinDistance = range.minDistance;
    settings.mMaxDistance = range.maxDistance;
  }
  settings.mNumPositionStepsOverride = LINK_POSITION_STEPS;
  return world.addConstraint(settings, a, b);
}

/** Lets b slide relative to a along `axis` only, optionally limited to [minMetres, maxMetres]. */
export function sliderLink(world: PhysicsWorld, a: BodyHandle, b: BodyHandle, worldPivot: Vec3Like, axis: Vec3Like, limits?: { minMetres: number; maxMetres: number }): Constraint {
  checkVec3(worldPivot, 'sliderLink', 'worldPivot');
  const s = normalized(axis, 'sliderLink', 'axis');
  const n = perpendicular(s);
  const J = world.jolt;
  const settings = new J.SliderConstraintSettings(); // consumed by addConstraint
  settings.mSpace = J.EConstraintSpace_WorldSpace;
  settings.mAutoDetectPoint = false;
  settings.mPoint1.Set(worldPivot.x, worldPivot.y, worldPivot.z);
  settings.mPoint2.Set(worldPivot.x, worldPivot.y, worldPivot.z);
  settings.mSliderAxis1.Set(s.x, s.y, s.z);
  settings.mSliderAxis2.Set(s.x, s.y, s.z);
  settings.mNormalAxis1.Set(n.x, n.y, n.z);
  settings.mNormalAxis2.Set(n.x, n.y, n.z);
  if (limits) {
    if (!(limits.minMetres <= 0 && limits.maxMetres >= 0)) {
      J.destroy(settings);
      throw new Error(`sliderLink: limits must satisfy min <= 0 <= max, got [${limits.minMetres}, ${limits.maxMetres}]`);
    }
    settings.mLimitsMin = limits.minMetres;
    settings.mLimitsMax = limits.maxMetres;
  }
  settings.mNumPositionStepsOverride = LINK_POSITION_STEPS;
  return world.addConstraint(settings, a, b);
}

/** A constraint the world tracks: the Jolt object (one reference is ours) and the stable ids it joins. */
interface TrackedConstraint {
  raw: Constraint;
  bodyA: number;
  bodyB: number;
}

/** The constraints of one world: created from settings (consumed), removed with their bodies or by clear(). */
export class ConstraintRegistry {
  private readonly J: JoltModule;
  private readonly system: InstanceType<JoltModule['PhysicsSystem']>;
  private readonly tracked: TrackedConstraint[] = [];

  constructor(J: JoltModule, system: InstanceType<JoltModule['PhysicsSystem']>) {
    this.J = J;
    this.system = system;
  }

  /** Creates and adds a constraint from `settings` (destroyed here) between two checked bodies. */
  add(settings: InstanceType<JoltModule['TwoBodyConstraintSettings']>, a: BodyHandle, b: BodyHandle): Constraint {
    const constraint = settings.Create(a.raw, b.raw); // ref count 0 until the AddRef below
    this.J.destroy(settings);
    constraint.AddRef(); // our reference, so the handle outlives RemoveConstraint until we Release it
    this.system.AddConstraint(constraint);
    this.tracked.push({ raw: constraint, bodyA: a.id, bodyB: b.id });
    return constraint;
  }

  /** Removes one constraint; false if it is not one of ours. */
  remove(constraint: Constraint): boolean {
    const ptr = this.J.getPointer(constraint);
    const i = this.tracked.findIndex((c) => this.J.getPointer(c.raw) === ptr);
    if (i < 0) return false;
    this.drop(i);
    return true;
  }

  /** Removes every constraint attached to body `id`; returns how many. */
  removeFor(id: number): number {
    let n = 0;
    for (let i = this.tracked.length - 1; i >= 0; i--) {
      const c = this.tracked[i];
      if (c.bodyA === id || c.bodyB === id) {
        this.drop(i);
        n++;
      }
    }
    return n;
  }

  /** Removes all constraints, newest first; returns how many. */
  clear(): number {
    const n = this.tracked.length;
    for (let i = n - 1; i >= 0; i--) this.drop(i);
    return n;
  }

  private drop(i: number): void {
    const c = this.tracked[i];
    this.tracked.splice(i, 1);
    this.system.RemoveConstraint(c.raw);
    c.raw.Release(); // our reference: the constraint is freed here
  }

  /** Number of live constraints. */
  get size(): number {
    return this.tracked.length;
  }
}
