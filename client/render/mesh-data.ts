// CPU-side triangle meshes (positions, normals, indices) and the helpers that combine them before upload.
// Winding: counter-clockwise seen from the side the normal points to (the renderer culls back faces).
import { quatRotate, type Vec3 } from './mat4.ts';

/** A triangle mesh ready for upload: per-vertex positions and unit normals, 32-bit triangle indices. */
export interface MeshData {
  positions: Float32Array<ArrayBuffer>;
  normals: Float32Array<ArrayBuffer>;
  indices: Uint32Array<ArrayBuffer>;
}

/** Incrementally builds a MeshData. */
export class MeshBuilder {
  private readonly pos: number[] = [];
  private readonly nrm: number[] = [];
  private readonly idx: number[] = [];

  /** Number of vertices added so far. */
  get vertexCount(): number {
    return this.pos.length / 3;
  }

  /** Adds a vertex and returns its index. */
  vertex(px: number, py: number, pz: number, nx: number, ny: number, nz: number): number {
    this.pos.push(px, py, pz);
    this.nrm.push(nx, ny, nz);
    return this.pos.length / 3 - 1;
  }

  /** Adds a triangle of existing vertex indices. */
  triangle(a: number, b: number, c: number): void {
    this.idx.push(a, b, c);
  }

  /** Adds a flat-shaded triangle (its own three vertices, face normal); skips degenerate ones. */
  flatTriangle(p: ArrayLike<number>, a: number, b: number, c: number): void {
    const ax = p[a * 3], ay = p[a * 3 + 1], az = p[a * 3 + 2];
    const bx = p[b * 3], by = p[b * 3 + 1], bz = p[b * 3 + 2];
    const cx = p[c * 3], cy = p[c * 3 + 1], cz = p[c * 3 + 2];
    const ux = bx - ax, uy = by - ay, uz = bz - az;
    const vx = cx - ax, vy = cy - ay, vz = cz - az;
    let nx = uy * vz - uz * vy;
    let ny = uz * vx - ux * vz;
    let nz = ux * vy - uy * vx;
    const len = Math.sqrt(nx * nx + ny * ny + nz * nz);
    if (!(len > 0)) return;
    nx /= len;
    ny /= len;
    nz /= len;
    const i = this.vertex(ax, ay, az, nx, ny, nz);
    this.vertex(bx, by, bz, nx, ny, nz);
    this.vertex(cx, cy, cz, nx, ny, nz);
    this.triangle(i, i + 1, i + 2);
  }

  /** Appends another mesh rotated by q and moved by t. */
  append(mesh: MeshData, t: Vec3 = [0, 0, 0], q: [number, number, number, number] = [0, 0, 0, 1]): void {
    const base = this.vertexCount;
    for (let v = 0; v < mesh.positions.length; v += 3) {
      const p = quatRotate(q[0], q[1], q[2], q[3], [mesh.positions[v], mesh.positions[v + 1], mesh.positions[v + 2]]);
      const nrm = quatRotate(q[0], q[1], q[2], q[3], [mesh.normals[v], mesh.normals[v + 1], mesh.normals[v + 2]]);
      this.vertex(p[0] + t[0], p[1] + t[1], p[2] + t[2], nrm[0], nrm[1], nrm[2]);
    }
    for (let i = 0; i < mesh.indices.length; i++) this.idx.push(mesh.indices[i] + base);
  }

  /** The finished mesh; throws if it has no triangles. */
  build(what: string): MeshData {
    if (this.idx.length === 0) throw new Error(`${what}: mesh has no triangles to draw`);
    return { positions: Float32Array.from(this.pos), normals: Float32Array.from(this.nrm), indices: Uint32Array.from(this.idx) };
  }
}

/** Axis-aligned bounds of a mesh's positions: [minX, minY, minZ, maxX, maxY, maxZ]. */
export function meshBounds(mesh: MeshData): [number, number, number, number, number, number] {
  const b: [number, number, number, number, number, number] = [Infinity, Infinity, Infinity, -Infinity, -Infinity, -Infinity];
  for (let i = 0; i < mesh.positions.length; i += 3) {
    for (let k = 0; k < 3; k++) {
      const v = mesh.positions[i + k];
      if (v < b[k]) b[k] = v;
      if (v > b[k + 3]) b[k + 3] = v;
    }
  }
  return b;
}
