// The body-state layout of a bulk state read: floats per body and the per-body flag bits. Plain data the physics
// wrapper writes and the snapshot codec and the server read.

/** Floats per body in a bulk state read: position 3, rotation 4, linear velocity 3, angular velocity 3. */
export const BODY_STATE_STRIDE = 13;

/** Bit flags per body in a bulk state read. */
export const BodyFlag = {
  Static: 1,
  Kinematic: 2,
  Dynamic: 4,
  Active: 8,
  Sensor: 16,
  Character: 32,
} as const;
