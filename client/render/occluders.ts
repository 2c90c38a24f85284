// What the follow camera must not look through: the static boxes of the scene (walls, blocks, the ground), as
// oriented boxes it can cast a ray against. Plain math on copies; nothing here touches the GPU.
import type { Vec3 } from './mat4.ts';

/** Static oriented boxes by body id (each stored as centre, rotation, half extents), with a first-hit ray cast. */
export class BoxOccluders {
  private readonly boxes = new Map<number, Float64Array>();

  /** Number of boxes held. */
  get size(): number {
    return this.boxes.size;
  }

  /** Adds (or replaces) a box: centre (m), unit rotation, half extents (m). */
  set(id: number, centre: { x: number; y: number; z: number }, rotation: { x: number; y: number; z: number; w: number }, halfExtents: { x: number; y: number; z: number }): void {
    this.boxes.set(id, Float64Array.of(centre.x, centre.y, centre.z, rotation.x, rotation.y, rotation.z, rotation.w, halfExtents.x, halfExtents.y, halfExtents.z));
  }

  /** Forgets a box. */
  delete(id: number): void {
    this.boxes.delete(id);
  }

  /** Forgets every box. */
  clear(): void {
    this.boxes.clear();
  }

  /**
   * The fraction along from → to where the segment first enters a box (1 when it hits none). Boxes that already
   * contain `from` are ignored, so a camera target standing inside a volume is not trapped.
   */
  castRay(from: Vec3, to: Vec3): number {
    let best = 1;
    const d: Vec3 = [to[0] - from[0], to[1] - from[1], to[2] - from[2]];
    for (const b of this.boxes.values()) {
      // Into the box's frame: rotate by the conjugate quaternion.
      const o = rotateInverse(b, [from[0] - b[0], from[1] - b[1], from[2] - b[2]]);
      const dir = rotateInverse(b, d);
      let tEnter = -Infinity;
      let tExit = Infinity;
      let inside = true;
      for (let k = 0; k < 3; k++) {
        const h = b[7 + k];
        if (Math.abs(o[k]) > h) inside = false;
        if (Math.abs(dir[k]) < 1e-12) {
          if (Math.abs(o[k]) > h) {
            tEnter = Infinity; // parallel and outside this slab: no hit
            break;
          }
          continue;
        }
        let t0 = (-h - o[k]) / dir[k];
        let t1 = (h - o[k]) / dir[k];
        if (t0 > t1) [t0, t1] = [t1, t0];
        tEnter = Math.max(tEnter, t0);
        tExit = Math.min(tExit, t1);
      }
      if (inside || tEnter > tExit || tExit < 0) continue;
      if (tEnter >= 0 && tEnter < best) best = tEnter;
    }
    return best;
  }
}

function rotateInverse(b: Float64Array, v: Vec3): Vec3 {
  const qx = -b[3];
  const qy = -b[4];
  const qz = -b[5];
  const qw = b[6];
  const tx = 2 * (qy * v[2] - qz * v[1]);
  const ty = 2 * (qz * v[0] - qx * v[2]);
  const tz = 2 * (qx * v[1] - qy * v[0]);
  return [v[0] + qw * tx + (qy * tz - qz * ty), v[1] + qw * ty + (qz * tx - qx * tz), v[2] + qw * tz + (qx * ty - qy * tx)];
}
