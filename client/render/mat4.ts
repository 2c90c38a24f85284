// Column-major 4×4 matrices and small vector helpers for the renderer (WebGPU clip space: depth in [0, 1]).
// Rendering only: nothing here feeds the simulation, so engine Math functions are fine.

/** A column-major 4×4 matrix, as WGSL's mat4x4f expects it. */
export type Mat4 = Float32Array;

/** A plain [x, y, z] triple. */
export type Vec3 = [number, number, number];

/** The identity matrix. */
export function mat4Identity(out: Mat4 = new Float32Array(16)): Mat4 {
  out.fill(0);
  out[0] = 1;
  out[5] = 1;
  out[10] = 1;
  out[15] = 1;
  return out;
}

/** out = a · b (out may alias a or b). */
export function mat4Multiply(a: Mat4, b: Mat4, out: Mat4 = new Float32Array(16)): Mat4 {
  const r = new Float32Array(16);
  for (let col = 0; col < 4; col++) {
    for (let row = 0; row < 4; row++) {
      let s = 0;
      for (let k = 0; k < 4; k++) s += a[k * 4 + row] * b[col * 4 + k];
      r[col * 4 + row] = s;
    }
  }
  out.set(r);
  return out;
}

/** A right-handed perspective projection mapping view depth [near, far] to clip depth [0, 1]. */
export function mat4Perspective(fovYRadians: number, aspect: number, nearMetres: number, farMetres: number, out: Mat4 = new Float32Array(16)): Mat4 {
  if (!(fovYRadians > 0 && fovYRadians < Math.PI)) throw new Error(`perspective: fovY must be in (0, π), got ${fovYRadians}`);
  if (!(aspect > 0) || !Number.isFinite(aspect)) throw new Error(`perspective: aspect must be > 0, got ${aspect}`);
  if (!(nearMetres > 0 && farMetres > nearMetres)) throw new Error(`perspective: need 0 < near < far, got ${nearMetres}, ${farMetres}`);
  const f = 1 / Math.tan(fovYRadians / 2);
  out.fill(0);
  out[0] = f / aspect;
  out[5] = f;
  out[10] = farMetres / (nearMetres - farMetres);
  out[11] = -1;
  out[14] = (nearMetres * farMetres) / (nearMetres - farMetres);
  return out;
}

/** A right-handed view matrix looking from `eye` at `target` with `up` as the up hint. */
export function mat4LookAt(eye: Vec3, target: Vec3, up: Vec3, out: Mat4 = new Float32Array(16)): Mat4 {
  let zx = eye[0] - target[0];
  let zy = eye[1] - target[1];
  let zz = eye[2] - target[2];
  let len = Math.sqrt(zx * zx + zy * zy + zz * zz);
  if (len < 1e-9) throw new Error('lookAt: eye and target coincide');
  zx /= len;
  zy /= len;
  zz /= len;
  // x = up × z
  let xx = up[1] * zz - up[2] * zy;
  let xy = up[2] * zx - up[0] * zz;
  let xz = up[0] * zy - up[1] * zx;
  len = Math.sqrt(xx * xx + xy * xy + xz * xz);
  if (len < 1e-9) {
    // Looking straight along `up`: pick any perpendicular axis.
    xx = 1;
    xy = 0;
    xz = 0;
  } else {
    xx /= len;
    xy /= len;
    xz /= len;
  }
  const yx = zy * xz - zz * xy;
  const yy = zz * xx - zx * xz;
  const yz = zx * xy - zy * xx;
  out[0] = xx;
  out[1] = yx;
  out[2] = zx;
  out[3] = 0;
  out[4] = xy;
  out[5] = yy;
  out[6] = zy;
  out[7] = 0;
  out[8] = xz;
  out[9] = yz;
  out[10] = zz;
  out[11] = 0;
  out[12] = -(xx * eye[0] + xy * eye[1] + xz * eye[2]);
  out[13] = -(yx * eye[0] + yy * eye[1] + yz * eye[2]);
  out[14] = -(zx * eye[0] + zy * eye[1] + zz * eye[2]);
  out[15] = 1;
  return out;
}

/** Transforms a point by m (with perspective divide); returns [x, y, z] in the target space. */
export function mat4TransformPoint(m: Mat4, p: Vec3): Vec3 {
  const x = m[0] * p[0] + m[4] * p[1] + m[8] * p[2] + m[12];
  const y = m[1] * p[0] + m[5] * p[1] + m[9] * p[2] + m[13];
  const z = m[2] * p[0] + m[6] * p[1] + m[10] * p[2] + m[14];
  const w = m[3] * p[0] + m[7] * p[1] + m[11] * p[2] + m[15];
  return [x / w, y / w, z / w];
}

/** Rotates v by the unit quaternion (qx, qy, qz, qw). */
export function quatRotate(qx: number, qy: number, qz: number, qw: number, v: Vec3): Vec3 {
  // t = 2 q×v; v' = v + w t + q×t
  const tx = 2 * (qy * v[2] - qz * v[1]);
  const ty = 2 * (qz * v[0] - qx * v[2]);
  const tz = 2 * (qx * v[1] - qy * v[0]);
  return [v[0] + qw * tx + (qy * tz - qz * ty), v[1] + qw * ty + (qz * tx - qx * tz), v[2] + qw * tz + (qx * ty - qy * tx)];
}
