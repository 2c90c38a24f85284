// Snapshot quantization: the format (position grid from the scenario's bounds, rotation bits) and the float ⇄ integer
// mappings for body poses (smallest-three quaternions) and character states. Pure arithmetic: no engine Math.
import type { Vec3Like } from '../physics-data/vectors.ts';
import { describeValue } from '../sim/describe-value.ts';

/** Largest position step (m) the default format allows on any axis: quantization error is at most half of it. */
export const DEFAULT_MAX_POSITION_STEP_METRES = 0.002;
/** Bits per smallest-three component by default (3 × 10 + 2-bit index = 32 bits per rotation). */
export const DEFAULT_ROTATION_BITS = 10;
/** Most bits one position axis may take; larger worlds get a coarser step. */
export const MAX_POSITION_BITS = 24;
/** Smallest and largest rotation component widths a format accepts. */
export const MIN_ROTATION_BITS = 6;
export const MAX_ROTATION_BITS = 15;
/** Character velocity step: 1/128 m/s, signed 16 bits (±256 m/s). */
export const VELOCITY_STEPS_PER_METRE_PER_SECOND = 128;
export const VELOCITY_LIMIT = 32767;
/** Yaw on the wire: 65536 steps per turn. Pitch: ±16384 steps for ±π/2. */
export const YAW_STEPS_PER_TURN = 65536;
export const PITCH_STEPS_PER_HALF_PI = 16384;

/** Ground states in their wire order (2 bits). */
export const GROUND_STATES = ['ground', 'steep', 'air', 'unsupported'] as const;
export type WireGroundState = (typeof GROUND_STATES)[number];

const TWO_PI = 2 * Math.PI;
const HALF_PI = Math.PI / 2;
/** Smallest-three components lie in [-1/√2, 1/√2]. */
const ROT_RANGE = Math.SQRT1_2;

/** An axis-aligned region in metres. */
export interface Bounds {
  min: Vec3Like;
  max: Vec3Like;
}

/** What the welcome message carries so the client builds the identical format. */
export interface SnapshotFormatSpec {
  /** Grid steps per axis (x, y, z): positions quantize to 0..steps. */
  positionSteps: [number, number, number];
  /** Bits per smallest-three component. */
  rotationBits: number;
}

/** A complete quantization format; both ends derive it from the bounds and the spec. */
export interface SnapshotFormat {
  readonly bounds: Readonly<Bounds>;
  readonly positionSteps: readonly [number, number, number];
  readonly positionBits: readonly [number, number, number];
  /** Size of one position step per axis (m). */
  readonly positionStepMetres: readonly [number, number, number];
  readonly rotationBits: number;
  /** Largest valid rotation component integer: 2^rotationBits − 2 (the centre, rotationMax / 2, is exactly zero). */
  readonly rotationMax: number;
}

function checkBounds(bounds: Bounds): void {
  if (!bounds || typeof bounds !== 'object' || !bounds.min || !bounds.max) throw new Error('snapshot format: bounds must be {min, max}');
  for (const axis of ['x', 'y', 'z'] as const) {
    const lo = bounds.min[axis];
    const hi = bounds.max[axis];
    if (typeof lo !== 'number' || typeof hi !== 'number' || !Number.isFinite(lo) || !Number.isFinite(hi)) {
      throw new Error(`snapshot format: bounds.${axis} must be finite numbers, got [${describeValue(lo)}, ${describeValue(hi)}]`);
    }
    if (!(hi > lo)) throw new Error(`snapshot format: bounds.max.${axis} (${hi}) must exceed bounds.min.${axis} (${lo})`);
  }
}

function bitsForSteps(steps: number): number {
  return 32 - Math.clz32(steps);
}

/** Chooses the grid for bounds: per axis the fewest steps with step ≤ maxStepMetres (capped at MAX_POSITION_BITS). */
export function createSnapshotFormat(bounds: Bounds, opts: { maxPositionStepMetres?: number; rotationBits?: number } = {}): SnapshotFormat {
  checkBounds(bounds);
  const maxStep = opts.maxPositionStepMetres ?? DEFAULT_MAX_POSITION_STEP_METRES;
  if (!Number.isFinite(maxStep) || maxStep <= 0) throw new Error(`snapshot format: maxPositionStepMetres must be > 0, got ${maxStep}`);
  const cap = ((1 << MAX_POSITION_BITS) >>> 0) - 1;
  const steps = (['x', 'y', 'z'] as const).map((axis) => {
    const extent = bounds.max[axis] - bounds.min[axis];
    return Math.max(1, Math.min(cap, Math.ceil(extent / maxStep)));
  }) as [number, number, number];
  return snapshotFormatFromSpec(bounds, { positionSteps: steps, rotationBits: opts.rotationBits ?? DEFAULT_ROTATION_BITS });
}

/** Rebuilds a format from bounds and a spec (the client does this with the welcome message); throws on bad values. */
export function snapshotFormatFromSpec(bounds: Bounds, spec: SnapshotFormatSpec): SnapshotFormat {
  checkBounds(bounds);
  const cap = ((1 << MAX_POSITION_BITS) >>> 0) - 1;
  if (!spec || !Array.isArray(spec.positionSteps) || spec.positionSteps.length !== 3) throw new Error('snapshot format: positionSteps must be 3 integers');
  for (const s of spec.positionSteps) {
    if (!Number.isInteger(s) || s < 1 || s > cap) throw new Error(`snapshot format: positionSteps must be integers in [1, ${cap}], got ${describeValue(s)}`);
  }
  const rb = spec.rotationBits;
  if (!Number.isInteger(rb) || rb < MIN_ROTATION_BITS || rb > MAX_ROTATION_BITS) {
    throw new Error(`snapshot format: rotationBits must be an integer in [${MIN_ROTATION_BITS}, ${MAX_ROTATION_BITS}], got ${describeValue(rb)}`);
  }
  const steps = [spec.positionSteps[0], spec.positionSteps[1], spec.positionSteps[2]] as const;
  const stepMetres = (axis: 'x' | 'y' | 'z', step: number): number => (bounds.max[axis] - bounds.min[axis]) / step;
  return Object.freeze({
    bounds: Object.freeze({ min: { ...bounds.min }, max: { ...bounds.max } }),
    positionSteps: steps,
    positionBits: [bitsForSteps(steps[0]), bitsForSteps(steps[1]), bitsForSteps(steps[2])] as const,
    positionStepMetres: [stepMetres('x', steps[0]), stepMetres('y', steps[1]), stepMetres('z', steps[2])] as const,
    rotationBits: rb,
    rotationMax: ((1 << rb) >>> 0) - 2,
  });
}

/** The spec to put in a welcome message. */
export function snapshotFormatSpec(format: SnapshotFormat): SnapshotFormatSpec {
  return { positionSteps: [format.positionSteps[0], format.positionSteps[1], format.positionSteps[2]], rotationBits: format.rotationBits };
}

/** Quantizes one coordinate on axis 0/1/2 to the grid (clamped to the bounds; NaN maps to 0). */
export function quantizeAxis(format: SnapshotFormat, axis: 0 | 1 | 2, metres: number): number {
  const key = axis === 0 ? 'x' : axis === 1 ? 'y' : 'z';
  const lo = format.bounds.min[key];
  const steps = format.positionSteps[axis];
  const q = Math.round((metres - lo) / format.positionStepMetres[axis]);
  if (!(q >= 0)) return 0;
  return q > steps ? steps : q;
}

/** The coordinate (m) of grid point q on an axis. */
export function dequantizeAxis(format: SnapshotFormat, axis: 0 | 1 | 2, q: number): number {
  const key = axis === 0 ? 'x' : axis === 1 ? 'y' : 'z';
  return format.bounds.min[key] + q * format.positionStepMetres[axis];
}

/**
 * Smallest-three: writes [index of the largest |component|, three others quantized] into out[offset..offset+3];
 * a component v ∈ [−1/√2, 1/√2] maps to round(v·√2·h) + h with h = 2^(bits−1) − 1, so zero is exact.
 * Sign convention: the quaternion is negated when its largest component is negative (q and −q are one rotation);
 * ties pick the lowest index (x, y, z, w order). A zero or NaN quaternion quantizes as identity.
 */
export function quantizeRotation(format: SnapshotFormat, x: number, y: number, z: number, w: number, out: Int32Array, offset: number): void {
  const ax = x < 0 ? -x : x;
  const ay = y < 0 ? -y : y;
  const az = z < 0 ? -z : z;
  const aw = w < 0 ? -w : w;
  // Lowest index wins ties: a later component must be strictly larger.
  let largest = 0;
  let largestAbs = ax;
  if (ay > largestAbs) {
    largest = 1;
    largestAbs = ay;
  }
  if (az > largestAbs) {
    largest = 2;
    largestAbs = az;
  }
  if (aw > largestAbs) {
    largest = 3;
    largestAbs = aw;
  }
  if (!(largestAbs > 0)) {
    x = 0;
    y = 0;
    z = 0;
    w = 1;
    largest = 3;
  }
  const norm = Math.sqrt(x * x + y * y + z * z + w * w);
  const big = largest === 0 ? x : largest === 1 ? y : largest === 2 ? z : w;
  const scale = ((big < 0 ? -1 : 1) / norm / ROT_RANGE) * (format.rotationMax / 2);
  out[offset] = largest;
  let k = offset + 1;
  if (largest !== 0) out[k++] = rotComponent(x * scale, format.rotationMax);
  if (largest !== 1) out[k++] = rotComponent(y * scale, format.rotationMax);
  if (largest !== 2) out[k++] = rotComponent(z * scale, format.rotationMax);
  if (largest !== 3) out[k++] = rotComponent(w * scale, format.rotationMax);
}

function rotComponent(scaled: number, max: number): number {
  const half = max / 2;
  let q = Math.round(scaled);
  if (!(q >= -half)) q = -half;
  else if (q > half) q = half;
  return q + half;
}

/** Writes the unit quaternion (x, y, z, w) for a quantized rotation into out[offset..offset+3]. */
export function dequantizeRotation(format: SnapshotFormat, index: number, a: number, b: number, c: number, out: Float32Array | Float64Array, offset: number): void {
  const half = format.rotationMax / 2;
  const va = ((a - half) / half) * ROT_RANGE;
  const vb = ((b - half) / half) * ROT_RANGE;
  const vc = ((c - half) / half) * ROT_RANGE;
  const rest = 1 - va * va - vb * vb - vc * vc;
  const vl = rest > 0 ? Math.sqrt(rest) : 0;
  const q = index === 0 ? [vl, va, vb, vc] : index === 1 ? [va, vl, vb, vc] : index === 2 ? [va, vb, vl, vc] : [va, vb, vc, vl];
  const n = Math.sqrt(q[0] * q[0] + q[1] * q[1] + q[2] * q[2] + q[3] * q[3]);
  out[offset] = q[0] / n;
  out[offset + 1] = q[1] / n;
  out[offset + 2] = q[2] / n;
  out[offset + 3] = q[3] / n;
}

/** Character velocity component (m/s) → signed integer in 1/128 m/s, clamped to ±VELOCITY_LIMIT. */
export function quantizeVelocity(metresPerSecond: number): number {
  const q = Math.round(metresPerSecond * VELOCITY_STEPS_PER_METRE_PER_SECOND);
  if (!(q === q)) return 0;
  return q > VELOCITY_LIMIT ? VELOCITY_LIMIT : q < -VELOCITY_LIMIT ? -VELOCITY_LIMIT : q;
}

/** Inverse of quantizeVelocity. */
export function dequantizeVelocity(q: number): number {
  return q / VELOCITY_STEPS_PER_METRE_PER_SECOND;
}

/** Yaw (radians, any value) → 0..65535 steps of a turn. */
export function quantizeYaw(yawRadians: number): number {
  if (!Number.isFinite(yawRadians)) return 0;
  const turn = yawRadians / TWO_PI;
  const q = Math.round((turn - Math.floor(turn)) * YAW_STEPS_PER_TURN);
  return q >= YAW_STEPS_PER_TURN ? q - YAW_STEPS_PER_TURN : q;
}

/** Inverse of quantizeYaw: radians in [0, 2π). */
export function dequantizeYaw(q: number): number {
  return (q / YAW_STEPS_PER_TURN) * TWO_PI;
}

/** Pitch (radians) → −16384..16384 (±π/2, clamped). */
export function quantizePitch(pitchRadians: number): number {
  if (!Number.isFinite(pitchRadians)) return 0;
  const q = Math.round((pitchRadians / HALF_PI) * PITCH_STEPS_PER_HALF_PI);
  return q > PITCH_STEPS_PER_HALF_PI ? PITCH_STEPS_PER_HALF_PI : q < -PITCH_STEPS_PER_HALF_PI ? -PITCH_STEPS_PER_HALF_PI : q;
}

/** Inverse of quantizePitch. */
export function dequantizePitch(q: number): number {
  return (q / PITCH_STEPS_PER_HALF_PI) * HALF_PI;
}

/** Ground state → its 2-bit wire code (unknown strings map to 'unsupported'). */
export function groundStateCode(state: string): number {
  const i = (GROUND_STATES as readonly string[]).indexOf(state);
  return i < 0 ? 3 : i;
}
