// A small deterministic 3-D quickhull: triangulates a convex-hull point cloud into outward-facing triangles.
// Same points in the same order ⇒ the same triangles in the same order (ties break by lowest point index).

interface HullFace {
  a: number;
  b: number;
  c: number;
  nx: number;
  ny: number;
  nz: number;
  /** Plane offset: distance(p) = n·p − offset. */
  offset: number;
  outside: number[];
  alive: boolean;
}

/** Relative tolerance: points within this fraction of the cloud's size from a plane count as on it. */
const RELATIVE_EPSILON = 1e-6;

function fail(message: string): never {
  throw new Error(`convex hull: ${message}`);
}

/**
 * The convex hull of `points` (x,y,z triples) as triangle indices into the points, counter-clockwise seen from
 * outside. Throws a clear Error for fewer than 4 points, non-finite values, or clouds with no volume.
 */
export function quickHull(points: ArrayLike<number>): Uint32Array {
  if (!points || typeof points.length !== 'number') fail('points must be an array of numbers');
  if (points.length % 3 !== 0) fail(`points must hold x,y,z triples (length ${points.length} is not a multiple of 3)`);
  const n = points.length / 3;
  if (n < 4) fail(`needs at least 4 points, got ${n}`);
  const p = new Float64Array(points.length);
  let scale = 0;
  for (let i = 0; i < points.length; i++) {
    const v = points[i];
    if (typeof v !== 'number' || !Number.isFinite(v)) fail(`points[${i}] must be a finite number, got ${String(v)}`);
    p[i] = v;
    scale = Math.max(scale, Math.abs(v));
  }
  const eps = Math.max(scale, 1e-30) * RELATIVE_EPSILON;

  const [i0, i1, i2, i3] = initialSimplex(p, n, eps);
  const faces: HullFace[] = [];
  const edges = new Map<number, number>();
  const cx = (p[i0 * 3] + p[i1 * 3] + p[i2 * 3] + p[i3 * 3]) / 4;
  const cy = (p[i0 * 3 + 1] + p[i1 * 3 + 1] + p[i2 * 3 + 1] + p[i3 * 3 + 1]) / 4;
  const cz = (p[i0 * 3 + 2] + p[i1 * 3 + 2] + p[i2 * 3 + 2] + p[i3 * 3 + 2]) / 4;
  for (const [a, b, c] of [[i0, i1, i2], [i0, i3, i1], [i1, i3, i2], [i2, i3, i0]] as const) {
    const f = makeFace(p, a, b, c, null);
    // Orient outward: the simplex centroid must lie below every face.
    if (f.nx * cx + f.ny * cy + f.nz * cz - f.offset > 0) addFace(faces, edges, n, makeFace(p, a, c, b, null));
    else addFace(faces, edges, n, f);
  }

  // Every other point goes to the face it is farthest above (first face on a tie); points below all are inside.
  for (let i = 0; i < n; i++) {
    if (i === i0 || i === i1 || i === i2 || i === i3) continue;
    assignPoint(p, faces, 0, i, eps);
  }

  for (let cursor = 0; cursor < faces.length; cursor++) {
    const face = faces[cursor];
    if (!face.alive || face.outside.length === 0) continue;
    addEyePoint(p, faces, edges, n, cursor, eps); // kills this face and appends the new ones
  }

  const out: number[] = [];
  for (const f of faces) if (f.alive) out.push(f.a, f.b, f.c);
  return Uint32Array.from(out);
}

function initialSimplex(p: Float64Array, n: number, eps: number): [number, number, number, number] {
  // Extremes on each axis (lowest index wins a tie), then the farthest pair among them.
  const extremes: number[] = [];
  for (let axis = 0; axis < 3; axis++) {
    let lo = 0;
    let hi = 0;
    for (let i = 1; i < n; i++) {
      if (p[i * 3 + axis] < p[lo * 3 + axis]) lo = i;
      if (p[i * 3 + axis] > p[hi * 3 + axis]) hi = i;
    }
    extremes.push(lo, hi);
  }
  let i0 = 0;
  let i1 = 0;
  let best = -1;
  for (let s = 0; s < extremes.length; s++) {
    for (let t = s + 1; t < extremes.length; t++) {
      const d = dist2(p, extremes[s], extremes[t]);
      if (d > best) {
        best = d;
        i0 = extremes[s];
        i1 = extremes[t];
      }
    }
  }
  if (Math.sqrt(best) <= eps) fail('all points coincide: the hull has no volume');
  // Farthest from the line i0–i1.
  const dx = p[i1 * 3] - p[i0 * 3];
  const dy = p[i1 * 3 + 1] - p[i0 * 3 + 1];
  const dz = p[i1 * 3 + 2] - p[i0 * 3 + 2];
  const dLen = Math.sqrt(dx * dx + dy * dy + dz * dz);
  let i2 = -1;
  best = eps;
  for (let i = 0; i < n; i++) {
    const vx = p[i * 3] - p[i0 * 3];
    const vy = p[i * 3 + 1] - p[i0 * 3 + 1];
    const vz = p[i * 3 + 2] - p[i0 * 3 + 2];
    const cx = vy * dz - vz * dy;
    const cy = vz * dx - vx * dz;
    const cz = vx * dy - vy * dx;
    const d = Math.sqrt(cx * cx + cy * cy + cz * cz) / dLen;
    if (d > best) {
      best = d;
      i2 = i;
    }
  }
  if (i2 < 0) fail('all points are collinear: the hull has no volume');
  // Farthest from the plane i0, i1, i2.
  const plane = makeFace(p, i0, i1, i2, null);
  let i3 = -1;
  best = eps;
  for (let i = 0; i < n; i++) {
    const d = Math.abs(plane.nx * p[i * 3] + plane.ny * p[i * 3 + 1] + plane.nz * p[i * 3 + 2] - plane.offset);
    if (d > best) {
      best = d;
      i3 = i;
    }
  }
  if (i3 < 0) fail('all points are coplanar: the hull has no volume');
  return [i0, i1, i2, i3];
}

function dist2(p: Float64Array, a: number, b: number): number {
  const x = p[a * 3] - p[b * 3];
  const y = p[a * 3 + 1] - p[b * 3 + 1];
  const z = p[a * 3 + 2] - p[b * 3 + 2];
  return x * x + y * y + z * z;
}

function makeFace(p: Float64Array, a: number, b: number, c: number, fallback: HullFace | null): HullFace {
  const ux = p[b * 3] - p[a * 3];
  const uy = p[b * 3 + 1] - p[a * 3 + 1];
  const uz = p[b * 3 + 2] - p[a * 3 + 2];
  const vx = p[c * 3] - p[a * 3];
  const vy = p[c * 3 + 1] - p[a * 3 + 1];
  const vz = p[c * 3 + 2] - p[a * 3 + 2];
  let nx = uy * vz - uz * vy;
  let ny = uz * vx - ux * vz;
  let nz = ux * vy - uy * vx;
  const len = Math.sqrt(nx * nx + ny * ny + nz * nz);
  if (len > 0) {
    nx /= len;
    ny /= len;
    nz /= len;
  } else if (fallback) {
    // A sliver: borrow the plane of the face it replaces so distances stay meaningful.
    nx = fallback.nx;
    ny = fallback.ny;
    nz = fallback.nz;
  }
  const offset = nx * p[a * 3] + ny * p[a * 3 + 1] + nz * p[a * 3 + 2];
  return { a, b, c, nx, ny, nz, offset, outside: [], alive: true };
}

function addFace(faces: HullFace[], edges: Map<number, number>, n: number, f: HullFace): number {
  const index = faces.length;
  faces.push(f);
  edges.set(f.a * n + f.b, index);
  edges.set(f.b * n + f.c, index);
  edges.set(f.c * n + f.a, index);
  return index;
}

function distance(p: Float64Array, f: HullFace, i: number): number {
  return f.nx * p[i * 3] + f.ny * p[i * 3 + 1] + f.nz * p[i * 3 + 2] - f.offset;
}

/** Puts point i on the face (from index `first` on) it is farthest above; returns false if it is above none. */
function assignPoint(p: Float64Array, faces: HullFace[], first: number, i: number, eps: number): boolean {
  let bestFace = -1;
  let best = eps;
  for (let f = first; f < faces.length; f++) {
    if (!faces[f].alive) continue;
    const d = distance(p, faces[f], i);
    if (d > best) {
      best = d;
      bestFace = f;
    }
  }
  if (bestFace < 0) return false;
  faces[bestFace].outside.push(i);
  return true;
}

function addEyePoint(p: Float64Array, faces: HullFace[], edges: Map<number, number>, n: number, seed: number, eps: number): void {
  const seedFace = faces[seed];
  let eye = seedFace.outside[0];
  let best = distance(p, seedFace, eye);
  for (const i of seedFace.outside) {
    const d = distance(p, seedFace, i);
    if (d > best) {
      best = d;
      eye = i;
    }
  }
  // Faces the eye sees, grown from the seed across shared edges (keeps the visible region connected).
  const visible: number[] = [seed];
  const isVisible = new Set<number>([seed]);
  const checked = new Set<number>([seed]);
  const horizon: Array<[number, number, number]> = []; // [u, v, owning visible face]
  for (let k = 0; k < visible.length; k++) {
    const f = faces[visible[k]];
    for (const [u, v] of [[f.a, f.b], [f.b, f.c], [f.c, f.a]] as const) {
      const neighbour = edges.get(v * n + u);
      if (neighbour === undefined) fail('internal error: open hull edge');
      if (isVisible.has(neighbour)) continue;
      if (!checked.has(neighbour) && distance(p, faces[neighbour], eye) > eps) {
        checked.add(neighbour);
        isVisible.add(neighbour);
        visible.push(neighbour);
        continue;
      }
      checked.add(neighbour);
      horizon.push([u, v, visible[k]]);
    }
  }
  const orphans: number[] = [];
  for (const fi of visible) {
    const f = faces[fi];
    f.alive = false;
    for (const i of f.outside) if (i !== eye) orphans.push(i);
    f.outside = [];
    for (const [u, v] of [[f.a, f.b], [f.b, f.c], [f.c, f.a]] as const) {
      if (edges.get(u * n + v) === fi) edges.delete(u * n + v);
    }
  }
  const firstNew = faces.length;
  for (const [u, v, owner] of horizon) {
    addFace(faces, edges, n, makeFace(p, u, v, eye, faces[owner]));
  }
  for (const i of orphans) assignPoint(p, faces, firstNew, i, eps);
}
