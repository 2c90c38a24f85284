// Unit primitives for the renderer: box (±1), sphere (r 1), cylinder (r 1, half-height 1) and capsules.
// Instances scale the unit shapes; capsules are built per height/radius ratio because their caps must stay round.
import { MeshBuilder, type MeshData } from './mesh-data.ts';

/** Segments around the Y axis for round shapes. */
export const ROUND_SEGMENTS = 16;
/** Rings from pole to pole for spheres (capsule caps use half of them each). */
export const SPHERE_RINGS = 8;

/** A cube spanning −1…1 on every axis with flat faces. */
export function unitBoxMesh(): MeshData {
  const m = new MeshBuilder();
  // Each face: normal axis, sign, then in-plane axes u, v with u × v = +axis; u is flipped with the sign so the
  // corners stay counter-clockwise seen from outside.
  const faces: Array<[number, number, number, number]> = [
    [0, 1, 1, 2], [0, -1, 1, 2], [1, 1, 2, 0], [1, -1, 2, 0], [2, 1, 0, 1], [2, -1, 0, 1],
  ];
  for (const [axis, sign, u, v] of faces) {
    const base = m.vertexCount;
    for (const [su, sv] of [[-1, -1], [1, -1], [1, 1], [-1, 1]]) {
      const p = [0, 0, 0];
      p[axis] = sign;
      p[u] = su * sign;
      p[v] = sv;
      const n = [0, 0, 0];
      n[axis] = sign;
      m.vertex(p[0], p[1], p[2], n[0], n[1], n[2]);
    }
    m.triangle(base, base + 1, base + 2);
    m.triangle(base, base + 2, base + 3);
  }
  return m.build('box');
}

/** A UV sphere of radius 1 with smooth normals. */
export function unitSphereMesh(segments = ROUND_SEGMENTS, rings = SPHERE_RINGS): MeshData {
  const m = new MeshBuilder();
  addRoundBand(m, segments, rings, 0, Math.PI, 0, 0);
  return m.build('sphere');
}

/** A capsule along Y: radius 1, cylinder half-height `halfHeightOverRadius` (scale it by the radius). */
export function unitCapsuleMesh(halfHeightOverRadius: number, segments = ROUND_SEGMENTS, rings = SPHERE_RINGS): MeshData {
  if (!(halfHeightOverRadius > 0) || !Number.isFinite(halfHeightOverRadius)) {
    throw new Error(`capsule: half-height / radius must be a finite number > 0, got ${halfHeightOverRadius}`);
  }
  const m = new MeshBuilder();
  const half = Math.max(2, Math.round(rings / 2));
  const h = halfHeightOverRadius;
  // Top cap (pole → equator) raised by h, straight wall, bottom cap (equator → pole) lowered by h.
  addRoundBand(m, segments, half, 0, Math.PI / 2, h, h);
  addRoundBand(m, segments, 1, Math.PI / 2, Math.PI / 2, h, -h);
  addRoundBand(m, segments, half, Math.PI / 2, Math.PI, -h, -h);
  return m.build('capsule');
}

/** A cylinder along Y: radius 1, half-height 1, smooth side and flat caps. */
export function unitCylinderMesh(segments = ROUND_SEGMENTS): MeshData {
  const m = new MeshBuilder();
  addRoundBand(m, segments, 1, Math.PI / 2, Math.PI / 2, 1, -1);
  for (const sign of [1, -1]) {
    const center = m.vertex(0, sign, 0, 0, sign, 0);
    const ring = m.vertexCount;
    for (let s = 0; s <= segments; s++) {
      const a = (s / segments) * Math.PI * 2;
      m.vertex(Math.sin(a), sign, Math.cos(a), 0, sign, 0);
    }
    for (let s = 0; s < segments; s++) {
      if (sign > 0) m.triangle(center, ring + s, ring + s + 1);
      else m.triangle(center, ring + s + 1, ring + s);
    }
  }
  return m.build('cylinder');
}

/**
 * Adds a band of a unit sphere between polar angles theta0 and theta1 (0 = +Y pole) in `rings` steps; the band's
 * first ring is moved up by yTop and its last ring by yBottom (so a zero-height band with yTop ≠ yBottom is a wall).
 */
function addRoundBand(m: MeshBuilder, segments: number, rings: number, theta0: number, theta1: number, yTop: number, yBottom: number): void {
  const base = m.vertexCount;
  for (let r = 0; r <= rings; r++) {
    const t = rings === 0 ? 0 : r / rings;
    const theta = theta0 + (theta1 - theta0) * t;
    const yOffset = yTop + (yBottom - yTop) * t;
    const sinT = Math.sin(theta);
    const cosT = Math.cos(theta);
    for (let s = 0; s <= segments; s++) {
      const a = (s / segments) * Math.PI * 2;
      const nx = sinT * Math.sin(a);
      const nz = sinT * Math.cos(a);
      m.vertex(nx, cosT + yOffset, nz, nx, cosT, nz);
    }
  }
  const stride = segments + 1;
  for (let r = 0; r < rings; r++) {
    for (let s = 0; s < segments; s++) {
      const a = base + r * stride + s;
      const b = a + stride;
      // Skip the zero-area triangles at the poles.
      const top = theta0 + ((theta1 - theta0) * r) / rings;
      const bottom = theta0 + ((theta1 - theta0) * (r + 1)) / rings;
      if (top > 1e-9) m.triangle(a, b, a + 1);
      if (Math.PI - bottom > 1e-9) m.triangle(a + 1, b, b + 1);
    }
  }
}
