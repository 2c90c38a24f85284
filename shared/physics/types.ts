// Plain value types of the physics API: motion kinds, sensor callbacks and the one BodyOptions every factory takes
// (vectors and quaternions: shared/physics-data/vectors.ts). No Jolt objects here: callers get copies.
import type { Vec3Like } from '../physics-data/vectors.ts';

/** How a body moves: nailed down, simulated, or driven by code. */
export type MotionKind = 'static' | 'dynamic' | 'kinematic';

/** Collision-detection quality for fast bodies: 'linearCast' turns on continuous collision (CCD). */
export type MotionQualityKind = 'discrete' | 'linearCast';

/** Callbacks that make a body a sensor; they run after the step, in (sensor id, other id) order. */
export interface SensorCallbacks<Other = unknown> {
  onEnter?: (other: Other | undefined) => void;
  onExit?: (other: Other | undefined) => void;
}

/** The tunables every body factory accepts. */
export interface BodyOptions<Other = unknown> {
  /** 'static' | 'dynamic' | 'kinematic'; default 'dynamic' (or from the legacy `dynamic` flag). */
  motion?: MotionKind;
  /** Legacy: false means static, true dynamic. `motion` wins when both are given. */
  dynamic?: boolean;
  /** Bounciness in [0, 1]; default 0.2. */
  restitution?: number;
  /** Friction, >= 0; Jolt's default (0.2) when absent. */
  friction?: number;
  /** Multiplier on gravity; default 1. */
  gravityFactor?: number;
  /** 'linearCast' for CCD on fast bodies. */
  motionQuality?: MotionQualityKind;
  /** The groups the body belongs to (CollisionLayer bits); default World for static, Prop otherwise. */
  layer?: number;
  /** The groups the body collides with; default CollisionLayer.All. */
  mask?: number;
  /** Detects overlaps without collision response. Implied by `sensor`. */
  isSensor?: boolean;
  /** Sensor callbacks (implies isSensor). */
  sensor?: SensorCallbacks<Other>;
  /** Initial linear velocity in m/s. */
  linearVelocity?: Vec3Like;
  /** Initial angular velocity in rad/s. */
  angularVelocity?: Vec3Like;
  /** Mass in kg (overrides the shape's density-derived mass). */
  massKg?: number;
  /** Linear damping (default Jolt's 0.05). */
  linearDamping?: number;
  /** Angular damping (default Jolt's 0.05). */
  angularDamping?: number;
  /** Whether the body may fall asleep when at rest; default true. */
  allowSleeping?: boolean;
  /** Anything the caller wants to find again on the handle. */
  userData?: unknown;
  /** A human-readable name (debugging, error messages). */
  name?: string;
  /** Bodies sharing this group id (an integer in [0, 0xfffffffe]) never collide with each other (a shooter, its bullets). */
  noCollideGroup?: number;
}
