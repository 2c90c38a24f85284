// Cameras: a third-person camera that trails the player's character, and an orbit camera for spectators.
// Both produce a CameraView; they hold only view state (angles, distances), never game state.
import { forwardFromYaw } from '../../shared/sim/controls.ts';
import type { Vec3 } from './mat4.ts';
import type { BoxOccluders } from './occluders.ts';
import type { CameraView } from './renderer.ts';

const FOV_Y_RADIANS = (60 * Math.PI) / 180;
const NEAR_METRES = 0.1;
const FAR_METRES = 600;

/** Trails a target from behind and above, looking where the player looks. */
export class FollowCamera {
  distanceMetres = 5.5;
  heightMetres = 1.6;
  /** Sideways offset to the right of the character (over the shoulder), so it does not hide the crosshair. */
  shoulderMetres = 0.6;
  /** How far in front of a wall the camera stops when the wall is between it and the character. */
  wallMarginMetres = 0.25;
  /** How fast the camera catches up with its target (1/s); higher = stiffer. */
  stiffnessPerSecond = 14;
  /**
   * Closest the camera may come to the character's head before it rises over what is in the way (a low wall behind
   * a player): closer than this the own capsule would fill the frame.
   */
  minDistanceMetres = 3;
  private smoothed: Vec3 | null = null;
  /** How far (radians) the camera boom is lowered below the look pitch (camera raised) to clear obstacles, eased. */
  private boomLift = 0;

  /** The view for a character whose feet are at `feet`, looking at yaw/pitch (radians); walls pull the camera in. */
  view(feet: Vec3, yawRadians: number, pitchRadians: number, dtSeconds: number, occluders?: BoxOccluders): CameraView {
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
    // Right of the view direction (yaw 0 faces −Z, so right is +X): (−f.z, 0, f.x).
    let shoulder = this.shoulderMetres;
    if (occluders && occluders.size > 0 && shoulder > 0) {
      // Standing beside a wall: keep the shoulder offset out of it.
      const side = occluders.castRay(t, [t[0] - f.z * shoulder, t[1], t[2] + f.x * shoulder]);
      if (side < 1) shoulder *= Math.max(0, side - this.wallMarginMetres / shoulder);
    }
    const pivot: Vec3 = [t[0] - f.z * shoulder, t[1], t[2] + f.x * shoulder];
    // Something close behind (a wall at the player's back): raise the boom until the camera has room, so it looks
    // over the obstacle instead of sitting inside the player's own capsule.
    let lift = 0;
    if (occluders && occluders.size > 0) {
      let best = -1;
      for (const candidate of BOOM_LIFTS_RADIANS) {
        const reach = this.boomEye(pivot, f, pitch - candidate, occluders).distance;
        if (reach > best + 0.25) {
          best = reach;
          lift = candidate;
        }
        if (reach >= this.minDistanceMetres) break;
      }
    }
    const ease = Number.isFinite(dtSeconds) && dtSeconds > 0 ? 1 - Math.exp(-6 * Math.min(dtSeconds, 0.25)) : 1;
    this.boomLift += (lift - this.boomLift) * ease;
    const eye = this.boomEye(pivot, f, pitch - this.boomLift, occluders).eye;
    const look: Vec3 = [pivot[0] + dir[0] * 4, pivot[1] + dir[1] * 4, pivot[2] + dir[2] * 4];
    return { eye, target: look, fovYRadians: FOV_Y_RADIANS, nearMetres: NEAR_METRES, farMetres: FAR_METRES };
  }

  /** Forgets the smoothed position (after a respawn or teleport). */
  reset(): void {
    this.smoothed = null;
    this.boomLift = 0;
  }

  // The camera at the end of a boom from the pivot along the look direction pitched by `boomPitch` (negative: looking
  // down, so the camera sits higher), pulled in before the first static box.
  private boomEye(pivot: Vec3, f: { x: number; z: number }, boomPitch: number, occluders?: BoxOccluders): { eye: Vec3; distance: number } {
    const p = Math.max(-MAX_BOOM_PITCH_RADIANS, Math.min(1.2, boomPitch));
    const cosP = Math.cos(p);
    const dir: Vec3 = [f.x * cosP, Math.sin(p), f.z * cosP];
    let eye: Vec3 = [pivot[0] - dir[0] * this.distanceMetres, Math.max(pivot[1] - dir[1] * this.distanceMetres, pivot[1] - 1.2), pivot[2] - dir[2] * this.distanceMetres];
    const full = Math.hypot(eye[0] - pivot[0], eye[1] - pivot[1], eye[2] - pivot[2]);
    if (!occluders || occluders.size === 0) return { eye, distance: full };
    // Keep both the head and the middle of the body in sight (a low wall may hide one and not the other).
    const body: Vec3 = [pivot[0], pivot[1] - this.heightMetres / 2, pivot[2]];
    const hit = Math.min(occluders.castRay(pivot, eye), occluders.castRay(body, [eye[0], eye[1] - this.heightMetres / 2, eye[2]]));
    if (hit >= 1) return { eye, distance: full };
    const k = Math.max(0, hit - this.wallMarginMetres / full);
    eye = [pivot[0] + (eye[0] - pivot[0]) * k, pivot[1] + (eye[1] - pivot[1]) * k, pivot[2] + (eye[2] - pivot[2]) * k];
    return { eye, distance: full * k };
  }
}

/** Boom lifts tried, in order, when the camera has no room behind the player (radians above the look pitch). */
const BOOM_LIFTS_RADIANS = [0, 0.3, 0.6, 0.9, 1.2] as const;
/** The boom never goes past this pitch (radians; straight down is π/2). */
const MAX_BOOM_PITCH_RADIANS = 1.35;

/** Circles a point; dragging turns it, the wheel zooms, and it drifts slowly when left alone. */
export class OrbitCamera {
  center: Vec3 = [0, 0, 0];
  radiusMetres = 30;
  azimuthRadians = 0.6;
  elevationRadians = 0.55;
  /** Idle drift (rad/s); 0 turns it off. */
  driftRadiansPerSecond = 0.08;

  /** Frames a box given by its min/max corners: its widest side spans most of a 16:9 view from above at an angle. */
  frame(min: Vec3, max: Vec3): void {
    // Scenes are wide rather than tall (a tall one is mostly sky above a pile): aim low, weigh height by half.
    this.center = [(min[0] + max[0]) / 2, min[1] + (max[1] - min[1]) * 0.3, (min[2] + max[2]) / 2];
    const span = Math.max(max[0] - min[0], (max[1] - min[1]) / 2, max[2] - min[2]);
    this.radiusMetres = Math.max(3, Math.min(300, span * 0.75));
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
