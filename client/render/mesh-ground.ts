// The surface height of the scene's static triangle meshes straight below a point, so blob shadows can lie on mesh
// terrain. Triangles are moved into world space once and bucketed in a uniform grid over x/z; a query walks only the
// triangles of one cell. Plain math on copies; nothing here touches the GPU.

/** A static mesh as the world view knows it: local vertex positions, triangle indices and its pose. */
export interface GroundMesh {
  positions: ArrayLike<number>;
  indices: ArrayLike<number>;
  position: { x: number; y: number; z: number };
  rotation: { x: number; y: number; z: number; w: number };
}

/** Aim for about this many triangles per grid cell. */
const TRIANGLES_PER_CELL = 4;
/** Most cells along one axis (bounds the grid's memory for huge, sparse meshes). */
const MAX_CELLS_PER_AXIS = 512;
/** Triangles nearly edge-on from above (|normal.y| below this) carry no ground. */
const MIN_UPWARD = 1e-6;

/** Highest mesh surface below a point, from a grid over x/z of world-space triangles. */
export class MeshGround {
  /** World-space triangles, 9 numbers each (three vertices). */
  private readonly triangles: Float64Array;
  private readonly minX: number;
  private readonly minZ: number;
  private readonly cellMetres: number;
  private readonly cellsX: number;
  private readonly cellsZ: number;
  /** Triangle indices per cell: cell c holds cellItems[cellStart[c] .. cellStart[c + 1]). */
  private readonly cellStart: Uint32Array;
  private readonly cellItems: Uint32Array;

  constructor(meshes: readonly GroundMesh[]) {
    let count = 0;
    for (const m of meshes) count += Math.floor(m.indices.length / 3);
    const tri = new Float64Array(count * 9);
    let minX = Infinity;
    let minZ = Infinity;
    let maxX = -Infinity;
    let maxZ = -Infinity;
    let t = 0;
    for (const m of meshes) {
      for (let i = 0; i + 2 < m.indices.length; i += 3) {
        for (let k = 0; k < 3; k++) {
          const v = m.indices[i + k] * 3;
          const w = toWorld(m, m.positions[v], m.positions[v + 1], m.positions[v + 2]);
          tri[t * 9 + k * 3] = w[0];
          tri[t * 9 + k * 3 + 1] = w[1];
          tri[t * 9 + k * 3 + 2] = w[2];
          minX = Math.min(minX, w[0]);
          maxX = Math.max(maxX, w[0]);
          minZ = Math.min(minZ, w[2]);
          maxZ = Math.max(maxZ, w[2]);
        }
        t++;
      }
    }
    this.triangles = tri;
    if (count === 0) {
      minX = minZ = maxX = maxZ = 0;
    }
    const spanX = Math.max(maxX - minX, 1e-6);
    const spanZ = Math.max(maxZ - minZ, 1e-6);
    const ideal = Math.sqrt((spanX * spanZ * TRIANGLES_PER_CELL) / Math.max(count, 1));
    this.cellMetres = Math.max(ideal, spanX / MAX_CELLS_PER_AXIS, spanZ / MAX_CELLS_PER_AXIS);
    this.minX = minX;
    this.minZ = minZ;
    this.cellsX = Math.max(1, Math.ceil(spanX / this.cellMetres));
    this.cellsZ = Math.max(1, Math.ceil(spanZ / this.cellMetres));
    // Two passes (count, then fill) so every cell's list is one slice of a flat array.
    const cells = this.cellsX * this.cellsZ;
    const counts = new Uint32Array(cells + 1);
    this.forEachCell(count, (_, c) => counts[c + 1]++);
    for (let c = 0; c < cells; c++) counts[c + 1] += counts[c];
    this.cellStart = counts.slice();
    const fill = counts.slice(0, cells);
    this.cellItems = new Uint32Array(counts[cells]);
    this.forEachCell(count, (triangle, c) => (this.cellItems[fill[c]++] = triangle));
  }

  /** Number of triangles held. */
  get size(): number {
    return this.triangles.length / 9;
  }

  /** The highest surface y at (x, z) that is not above `y`, or null when no triangle lies below the point there. */
  surfaceBelow(x: number, y: number, z: number): number | null {
    if (this.size === 0) return null;
    const cx = Math.floor((x - this.minX) / this.cellMetres);
    const cz = Math.floor((z - this.minZ) / this.cellMetres);
    if (cx < 0 || cz < 0 || cx >= this.cellsX || cz >= this.cellsZ) return null;
    const c = cz * this.cellsX + cx;
    const tri = this.triangles;
    let best: number | null = null;
    for (let i = this.cellStart[c]; i < this.cellStart[c + 1]; i++) {
      const o = this.cellItems[i] * 9;
      const h = heightOnTriangle(tri, o, x, z);
      if (h !== null && h <= y && (best === null || h > best)) best = h;
    }
    return best;
  }

  private forEachCell(count: number, visit: (triangle: number, cell: number) => void): void {
    const tri = this.triangles;
    for (let t = 0; t < count; t++) {
      const o = t * 9;
      const x0 = Math.min(tri[o], tri[o + 3], tri[o + 6]);
      const x1 = Math.max(tri[o], tri[o + 3], tri[o + 6]);
      const z0 = Math.min(tri[o + 2], tri[o + 5], tri[o + 8]);
      const z1 = Math.max(tri[o + 2], tri[o + 5], tri[o + 8]);
      const ax = this.cellIndex(x0 - this.minX, this.cellsX);
      const bx = this.cellIndex(x1 - this.minX, this.cellsX);
      const az = this.cellIndex(z0 - this.minZ, this.cellsZ);
      const bz = this.cellIndex(z1 - this.minZ, this.cellsZ);
      for (let cz = az; cz <= bz; cz++) for (let cx = ax; cx <= bx; cx++) visit(t, cz * this.cellsX + cx);
    }
  }

  private cellIndex(offsetMetres: number, cells: number): number {
    return Math.min(cells - 1, Math.max(0, Math.floor(offsetMetres / this.cellMetres)));
  }
}

/** The y of the triangle at `o` above (x, z), or null when (x, z) falls outside it seen from above. */
function heightOnTriangle(t: Float64Array, o: number, x: number, z: number): number | null {
  const ax = t[o];
  const az = t[o + 2];
  const e1x = t[o + 3] - ax;
  const e1z = t[o + 5] - az;
  const e2x = t[o + 6] - ax;
  const e2z = t[o + 8] - az;
  const det = e1x * e2z - e2x * e1z;
  if (Math.abs(det) < MIN_UPWARD) return null;
  const px = x - ax;
  const pz = z - az;
  const u = (px * e2z - e2x * pz) / det;
  const v = (e1x * pz - px * e1z) / det;
  const eps = 1e-9;
  if (u < -eps || v < -eps || u + v > 1 + eps) return null;
  return t[o + 1] + u * (t[o + 4] - t[o + 1]) + v * (t[o + 7] - t[o + 1]);
}

// A local vertex moved by the mesh's rotation and position.
function toWorld(m: GroundMesh, x: number, y: number, z: number): [number, number, number] {
  const { x: qx, y: qy, z: qz, w: qw } = m.rotation;
  // v + 2w(q × v) + 2 q × (q × v)
  const cx = qy * z - qz * y;
  const cy = qz * x - qx * z;
  const cz = qx * y - qy * x;
  const rx = x + 2 * (qw * cx + qy * cz - qz * cy);
  const ry = y + 2 * (qw * cy + qz * cx - qx * cz);
  const rz = z + 2 * (qw * cz + qx * cy - qy * cx);
  return [rx + m.position.x, ry + m.position.y, rz + m.position.z];
}
