// Smoothing of corrections for renderers: when a rollback moves a body, the body keeps its on-screen pose through a
// visual offset (position and rotation) that decays to zero over a short half-life, so corrections glide instead of
// popping. Render-side only: nothing here feeds the simulation.
import { BODY_STATE_STRIDE, BodyFlag } from '../../shared/physics-data/body-state.ts';

/** A bulk body read (ids ascending, BODY_STATE_STRIDE floats per body, BodyFlag bits). */
export interface BodyRead {
  count: number;
  ids: Uint32Array;
  states: Float32Array;
  flags: Uint8Array;
}

/** Position (3) and rotation quaternion (4) offsets of one body. */
type Offset = Float64Array;

/** Visual poses of moving bodies by id, as captured before a rollback. */
export type PoseCapture = Map<number, Float64Array>;

function mulQuat(ax: number, ay: number, az: number, aw: number, bx: number, by: number, bz: number, bw: number, out: Float64Array, o: number): void {
  out[o] = aw * bx + ax * bw + ay * bz - az * by;
  out[o + 1] = aw * by - ax * bz + ay * bw + az * bx;
  out[o + 2] = aw * bz + ax * by - ay * bx + az * bw;
  out[o + 3] = aw * bw - ax * bx - ay * by - az * bz;
}

/** Keeps the visual offsets of corrected bodies and applies them to reads. */
export class CorrectionSmoother {
  readonly halfLifeMs: number;
  private readonly offsets = new Map<number, Offset>();
  private readonly scratch = new Float64Array(7);

  constructor(halfLifeMs = 80) {
    if (!(halfLifeMs >= 0)) throw new Error('CorrectionSmoother: halfLifeMs must be ≥ 0');
    this.halfLifeMs = halfLifeMs;
  }

  /** Bodies with an offset still decaying. */
  get activeCount(): number {
    return this.offsets.size;
  }

  /** The on-screen poses of the moving bodies in `read` (call before the rollback changes them). */
  capture(read: BodyRead): PoseCapture {
    const out: PoseCapture = new Map();
    for (let i = 0; i < read.count; i++) {
      if (read.flags[i] & BodyFlag.Static) continue;
      const pose = new Float64Array(7);
      this.visualPose(read, i, pose);
      out.set(read.ids[i], pose);
    }
    return out;
  }

  /**
   * Sets offsets so the bodies of `read` (after the rollback) keep the on-screen poses of `before`. Returns the
   * largest position jump hidden (m).
   */
  correct(before: PoseCapture, read: BodyRead): number {
    let largest = 0;
    for (let i = 0; i < read.count; i++) {
      const old = before.get(read.ids[i]);
      if (!old) continue;
      const b = i * BODY_STATE_STRIDE;
      const s = read.states;
      const dx = old[0] - s[b];
      const dy = old[1] - s[b + 1];
      const dz = old[2] - s[b + 2];
      // offsetRotation = oldVisual · conjugate(new)
      mulQuat(old[3], old[4], old[5], old[6], -s[b + 3], -s[b + 4], -s[b + 5], s[b + 6], this.scratch, 3);
      const jump = Math.hypot(dx, dy, dz);
      const turn = 1 - Math.abs(this.scratch[6]);
      if (jump < 1e-5 && turn < 1e-7) {
        this.offsets.delete(read.ids[i]);
        continue;
      }
      largest = Math.max(largest, jump);
      const o = new Float64Array(7);
      o[0] = dx;
      o[1] = dy;
      o[2] = dz;
      o.set(this.scratch.subarray(3, 7), 3);
      this.offsets.set(read.ids[i], o);
    }
    return largest;
  }

  /** Lets the offsets decay by `elapsedMs`; offsets that have become invisible are dropped. */
  decay(elapsedMs: number): void {
    if (this.offsets.size === 0 || !(elapsedMs > 0)) return;
    const keep = this.halfLifeMs === 0 ? 0 : Math.pow(0.5, elapsedMs / this.halfLifeMs);
    for (const [id, o] of this.offsets) {
      o[0] *= keep;
      o[1] *= keep;
      o[2] *= keep;
      // nlerp of the rotation offset towards identity
      const w = o[6] < 0 ? -1 : 1;
      o[3] *= keep;
      o[4] *= keep;
      o[5] *= keep;
      o[6] = o[6] * keep + w * (1 - keep);
      const n = Math.hypot(o[3], o[4], o[5], o[6]);
      for (let k = 3; k < 7; k++) o[k] /= n;
      if (Math.hypot(o[0], o[1], o[2]) < 1e-4 && 1 - Math.abs(o[6]) < 1e-8) this.offsets.delete(id);
    }
  }

  /** A copy of `read` with every offset applied (the poses to draw). */
  apply(read: BodyRead): BodyRead {
    const states = read.states.slice(0, read.count * BODY_STATE_STRIDE);
    const out = { count: read.count, ids: read.ids.slice(0, read.count), states, flags: read.flags.slice(0, read.count) };
    if (this.offsets.size === 0) return out;
    const pose = new Float64Array(7);
    for (let i = 0; i < out.count; i++) {
      if (!this.offsets.has(out.ids[i])) continue;
      this.visualPose(read, i, pose);
      states.set(pose, i * BODY_STATE_STRIDE);
    }
    return out;
  }

  /** The position offset of a body (m), or null when it has none. */
  positionOffset(id: number): [number, number, number] | null {
    const o = this.offsets.get(id);
    return o ? [o[0], o[1], o[2]] : null;
  }

  /** Forgets every offset (a resync starts a new world). */
  clear(): void {
    this.offsets.clear();
  }

  private visualPose(read: BodyRead, i: number, out: Float64Array): void {
    const b = i * BODY_STATE_STRIDE;
    const s = read.states;
    const o = this.offsets.get(read.ids[i]);
    if (!o) {
      for (let k = 0; k < 7; k++) out[k] = s[b + k];
      return;
    }
    out[0] = s[b] + o[0];
    out[1] = s[b + 1] + o[1];
    out[2] = s[b + 2] + o[2];
    mulQuat(o[3], o[4], o[5], o[6], s[b + 3], s[b + 4], s[b + 5], s[b + 6], out, 3);
  }
}
