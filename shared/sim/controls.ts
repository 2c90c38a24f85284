// The control conventions every layer shares: how a command's move axes, yaw and pitch become a world-space walk
// velocity and an aim direction. Arithmetic and det-math only, so server, replay and client agree to the bit.
import type { Vec3Like } from '../physics-data/vectors.ts';
import { detCos, detSin } from './det-math.ts';
import { MOVE_STEPS, PITCH_STEPS, YAW_STEPS, type InputCommand } from './input.ts';

const TWO_PI = 6.283185307179586;
const HALF_PI = 1.5707963267948966;

/** Sprint multiplies the walk speed by this. */
export const SPRINT_FACTOR = 1.8;

/** Yaw of a command in radians, [0, 2π): 0 faces -Z, growing counter-clockwise seen from above (about +Y). */
export function commandYawRadians(cmd: InputCommand): number {
  return (cmd.yaw / YAW_STEPS) * TWO_PI;
}

/** Pitch of a command in radians, [-π/2, π/2]: positive looks up. */
export function commandPitchRadians(cmd: InputCommand): number {
  return (cmd.pitch / PITCH_STEPS) * HALF_PI;
}

/** Unit forward vector on the ground for a yaw: (-sin yaw, 0, -cos yaw). */
export function forwardFromYaw(yawRadians: number): Vec3Like {
  return { x: -detSin(yawRadians), y: 0, z: -detCos(yawRadians) };
}

/**
 * The horizontal velocity (m/s) a command asks for: moveX strafes right (+) / left (-), moveZ walks forward (+) /
 * back (-), rotated by yaw; diagonals are clamped to unit length; Sprint multiplies by SPRINT_FACTOR.
 */
export function walkVelocity(cmd: InputCommand, walkSpeedMetresPerSecond: number, sprinting: boolean): { x: number; z: number } {
  let mx = cmd.moveX / MOVE_STEPS;
  let mz = cmd.moveZ / MOVE_STEPS;
  const lenSq = mx * mx + mz * mz;
  if (lenSq > 1) {
    const inv = 1 / Math.sqrt(lenSq);
    mx *= inv;
    mz *= inv;
  }
  const yaw = commandYawRadians(cmd);
  const s = detSin(yaw);
  const c = detCos(yaw);
  // right = (cos, 0, -sin), forward = (-sin, 0, -cos)
  const speed = walkSpeedMetresPerSecond * (sprinting ? SPRINT_FACTOR : 1);
  return { x: (mx * c - mz * s) * speed, z: (-mx * s - mz * c) * speed };
}

/** Unit aim direction of a command: forward tilted up by pitch. */
export function aimDirection(cmd: InputCommand): Vec3Like {
  const yaw = commandYawRadians(cmd);
  const pitch = commandPitchRadians(cmd);
  const cp = detCos(pitch);
  return { x: -detSin(yaw) * cp, y: detSin(pitch), z: -detCos(yaw) * cp };
}
