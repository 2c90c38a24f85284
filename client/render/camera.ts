// Cameras: a third-person camera that trails the player's character, and an orbit camera for spectators.
// Both produce a CameraView; they hold only view state (angles, distances), never game state.
import { forwardFromYaw } from '../../shared/sim/controls.ts';
import type { Vec3 } from './mat4.ts';
import type { CameraView } from './renderer.ts';

const FOV_Y_RADIANS = (60 * Math.PI) / 180;
const NEAR_METRES = 0.1;
const FAR_METRES = 600;

/** Trails a target from behind and above, looking where the player looks. */
export class FollowCamera {
  distanceMetres = 5.5;
  heightMetres = 1.6;
  /** How fast the camera catches up with its target (1/s); higher = stiffer. */
  stiffnessPerSecond = 14;
  private smoothed: Vec3 | null = null;

  /** The view for a character whose feet are at `feet`, looking at yaw/pitch (radians). */
  view(feet: Vec3, yawRadians: number, pitchRadians: number, dtSeconds: number): CameraView {
    const target: Vec3 = [feet[0], feet[1] + this.heightMetres, feet[2]];
    if (!this.smoothed || !Number.isFinite(dtSeconds)) this.smoothed = target;
    else {
      const k = 1 - Math.exp(-this.stiffnessPerSecond * Math.max(0, Math.min(dtSeconds, 0.25)));
      for (let i = 0; i < 3; i++) this.smoothed[i] += (target[i] - this.smoothed[i]) * k;
    }
    const t = this.smoothed;
    const pitch = Math.max(-1.2, Math.min(1.2, pitchRadians));
    // The simulation's convention (shared/sim/controls.ts): yaw 0 faces −Z, growing counter-clockwise from above.
    const f = forwardFromYaw(yawRadians);
    const cosP = Math.cos(pitch);
    const dir: Vec3 = [f.x * cosP, Math.sin(pitch), f.z * cosP];
    const eye: Vec3 = [t[0] - dir[0] * this.distanceMetres, Math.max(t[1] - dir[1] * this.distanceMetres, t[1] - 1.2), t[2] - dir[2] * this.distanceMetres];
    const look: Vec3 = [t[0] + dir[0] * 4, t[1] + dir[1] * 4, t[2] + dir[2] * 4];
    return { eye, target: look, fovYRadians: FOV_Y_RADIANS, nearMetres: NEAR_METRES, farMetres: FAR_METRES };
  }

  /** Forgets the smoothed position (after a respawn or teleport). */
  reset(): void {
    this.smoothed = null;
  }
}

/** Circles a point; dragging turns it, the wheel zooms, and it drifts slowly when left alone. */
export class OrbitCamera {
  center: Vec3 = [0, 0, 0];
  radiusMetres = 30;
  azimuthRadians = 0.6;
  elevationRadians = 0.55;
  /** Idle drift (rad/s); 0 turns it off. */
  driftRadiansPerSecond = 0.08;

  /** Frames a box given by its min/max corners. */
  frame(min: Vec3, max: Vec3): void {
    this.center = [(min[0] + max[0]) / 2, Math.max(min[1], 0) + Math.min(4, (max[1] - min[1]) / 4), (min[2] + max[2]) / 2];
    const span = Math.max(max[0] - min[0], max[2] - min[2], 4);
    this.radiusMetres = Math.min(150, span * 0.85);
  }

  /** Turns the camera by a pointer drag in pixels. */
  drag(dxPx: number, dyPx: number): void {
    this.azimuthRadians -= dxPx * 0.006;
    this.elevationRadians = Math.max(0.05, Math.min(1.45, this.elevationRadians + dyPx * 0.006));
  }

  /** Zooms by a wheel delta (positive = out). */
  zoom(deltaY: number): void {
    this.radiusMetres = Math.max(3, Math.min(300, this.radiusMetres * Math.exp(deltaY * 0.001)));
  }

  /** The view after advancing the idle drift by dtSeconds. */
  view(dtSeconds: number): CameraView {
    if (Number.isFinite(dtSeconds)) this.azimuthRadians += this.driftRadiansPerSecond * Math.max(0, Math.min(dtSeconds, 0.25));
    const r = this.radiusMetres;
    const cosE = Math.cos(this.elevationRadians);
    const eye: Vec3 = [
      this.center[0] + r * cosE * Math.sin(this.azimuthRadians),
      this.center[1] + r * Math.sin(this.elevationRadians),
      this.center[2] + r * cosE * Math.cos(this.azimuthRadians),
    ];
    return { eye, target: [...this.center], fovYRadians: FOV_Y_RADIANS, nearMetres: NEAR_METRES, farMetres: FAR_METRES };
  }
}
