// Deterministic trigonometry for simulation code: arithmetic-only polynomials (no Math.sin/cos/atan2, whose
// results may differ between JS engines). Accurate to ~1e-7 rad/unit, plenty for gameplay directions.

const TWO_PI = 6.283185307179586;
const HALF_PI = 1.5707963267948966;
const PI = 3.141592653589793;

/** Reduces an angle to [-π, π] with arithmetic only. */
export function wrapAngle(radians: number): number {
  const turns = Math.floor((radians + PI) / TWO_PI);
  return radians - turns * TWO_PI;
}

/** sin(x) for |x| <= π/2: a degree-11 odd Taylor polynomial (error < 6e-8). */
function sinKernel(x: number): number {
  const x2 = x * x;
  return x * (1 + x2 * (-1 / 6 + x2 * (1 / 120 + x2 * (-1 / 5040 + x2 * (1 / 362880 + x2 * (-1 / 39916800))))));
}

/** Deterministic sine. */
export function detSin(radians: number): number {
  let x = wrapAngle(radians);
  if (x > HALF_PI) x = PI - x;
  else if (x < -HALF_PI) x = -PI - x;
  return sinKernel(x);
}

/** Deterministic cosine. */
export function detCos(radians: number): number {
  return detSin(radians + HALF_PI);
}

/** Deterministic atan for any x (range reduction + odd polynomial). */
export function detAtan(x: number): number {
  if (x !== x) return x;
  const sign = x < 0 ? -1 : 1;
  let a = x * sign;
  let offset = 0;
  if (a > 1) {
    a = 1 / a;
    offset = HALF_PI;
  }
  // atan(a) = 2·atan(a / (1 + sqrt(1 + a²))) halves the argument twice for fast convergence.
  let t = a / (1 + Math.sqrt(1 + a * a));
  t = t / (1 + Math.sqrt(1 + t * t));
  const t2 = t * t;
  const poly = t * (1 + t2 * (-1 / 3 + t2 * (1 / 5 + t2 * (-1 / 7 + t2 * (1 / 9 + t2 * (-1 / 11))))));
  const r = 4 * poly;
  return sign * (offset ? offset - r : r);
}

/** Deterministic atan2(y, x). */
export function detAtan2(y: number, x: number): number {
  if (x > 0) return detAtan(y / x);
  if (x < 0) return y >= 0 ? detAtan(y / x) + PI : detAtan(y / x) - PI;
  if (y > 0) return HALF_PI;
  if (y < 0) return -HALF_PI;
  return 0;
}

/** A unit quaternion rotating `radians` about the Y axis. */
export function quatFromYaw(radians: number): { x: number; y: number; z: number; w: number } {
  const half = radians * 0.5;
  return { x: 0, y: detSin(half), z: 0, w: detCos(half) };
}

/** A unit quaternion rotating `radians` about a unit axis. */
export function quatFromAxisAngle(axis: { x: number; y: number; z: number }, radians: number): { x: number; y: number; z: number; w: number } {
  const s = detSin(radians * 0.5);
  return { x: axis.x * s, y: axis.y * s, z: axis.z * s, w: detCos(radians * 0.5) };
}
