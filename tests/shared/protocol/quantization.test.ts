// Tests of snapshot quantization: the position grid chosen from bounds, smallest-three rotations with their sign
// convention, and character fields (velocity, yaw, pitch, ground state).
import { describe, expect, it } from 'vitest';
import {
  createSnapshotFormat,
  dequantizeAxis,
  dequantizePitch,
  dequantizeRotation,
  dequantizeVelocity,
  dequantizeYaw,
  groundStateCode,
  quantizeAxis,
  quantizePitch,
  quantizeRotation,
  quantizeVelocity,
  quantizeYaw,
  snapshotFormatFromSpec,
  snapshotFormatSpec,
} from '../../../shared/protocol/quantization.ts';
import { Prng } from '../../../shared/sim/prng.ts';

const bounds = { min: { x: -50, y: -10, z: -50 }, max: { x: 50, y: 40, z: 50 } };

function randomQuat(rng: Prng): [number, number, number, number] {
  // Gaussian-ish components (sum of uniforms) normalised: covers every orientation.
  const g = (): number => rng.next() + rng.next() + rng.next() - 1.5;
  const q = [g(), g(), g(), g()];
  const n = Math.hypot(...q);
  return [q[0] / n, q[1] / n, q[2] / n, q[3] / n];
}

function quantizeQ(format: ReturnType<typeof createSnapshotFormat>, q: readonly number[]): Int32Array {
  const out = new Int32Array(4);
  quantizeRotation(format, q[0], q[1], q[2], q[3], out, 0);
  return out;
}

describe('quantization', () => {
  it('chooses a grid of at most 2 mm per step and the fewest bits for the bounds', () => {
    const f = createSnapshotFormat(bounds);
    expect(f.positionSteps).toEqual([50000, 25000, 50000]);
    expect(f.positionBits).toEqual([16, 15, 16]);
    for (const s of f.positionStepMetres) expect(s).toBeLessThanOrEqual(0.002);
  });

  it('keeps every position within half a step of the truth and clamps outside the bounds', () => {
    const f = createSnapshotFormat(bounds);
    const rng = new Prng(3);
    let worst = 0;
    for (let i = 0; i < 20000; i++) {
      const x = rng.range(-50, 50);
      const q = quantizeAxis(f, 0, x);
      worst = Math.max(worst, Math.abs(dequantizeAxis(f, 0, q) - x));
    }
    expect(worst).toBeLessThanOrEqual(0.001 + 1e-9);
    expect(quantizeAxis(f, 1, -99)).toBe(0);
    expect(quantizeAxis(f, 1, 99)).toBe(f.positionSteps[1]);
    expect(quantizeAxis(f, 2, Number.NaN)).toBe(0);
  });

  it('caps huge worlds at 24 bits per axis with a coarser step', () => {
    const f = createSnapshotFormat({ min: { x: -1e5, y: 0, z: 0 }, max: { x: 1e5, y: 1, z: 1 } });
    expect(f.positionBits[0]).toBe(24);
    expect(f.positionStepMetres[0]).toBeGreaterThan(0.002);
  });

  it('rejects empty, inverted or non-finite bounds and bad rotation widths with clear errors', () => {
    expect(() => createSnapshotFormat({ min: { x: 0, y: 0, z: 0 }, max: { x: 0, y: 1, z: 1 } })).toThrow(/must exceed/);
    expect(() => createSnapshotFormat({ min: { x: 0, y: Number.NaN, z: 0 }, max: { x: 1, y: 1, z: 1 } })).toThrow(/finite/);
    expect(() => createSnapshotFormat(bounds, { rotationBits: 3 })).toThrow(/rotationBits/);
    expect(() => createSnapshotFormat(bounds, { maxPositionStepMetres: 0 })).toThrow(/maxPositionStepMetres/);
    expect(() => snapshotFormatFromSpec(bounds, { positionSteps: [1, 2, 1.5] as [number, number, number], rotationBits: 10 })).toThrow(/positionSteps/);
  });

  it('rebuilds the identical format on the client from bounds and the welcome spec', () => {
    const f = createSnapshotFormat(bounds, { rotationBits: 12 });
    const g = snapshotFormatFromSpec(bounds, snapshotFormatSpec(f));
    expect(g).toEqual(f);
  });

  it('keeps rotations within 0.25 degrees with 3 × 10-bit smallest-three', () => {
    const f = createSnapshotFormat(bounds);
    const rng = new Prng(5);
    const out = new Float64Array(4);
    let worstRad = 0;
    for (let i = 0; i < 20000; i++) {
      const q = randomQuat(rng);
      const qi = quantizeQ(f, q);
      dequantizeRotation(f, qi[0], qi[1], qi[2], qi[3], out, 0);
      expect(Math.hypot(out[0], out[1], out[2], out[3])).toBeCloseTo(1, 12);
      const dot = Math.abs(q[0] * out[0] + q[1] * out[1] + q[2] * out[2] + q[3] * out[3]);
      worstRad = Math.max(worstRad, 2 * Math.acos(Math.min(1, dot)));
    }
    expect((worstRad * 180) / Math.PI).toBeLessThan(0.25);
    expect(worstRad).toBeGreaterThan(0);
  });

  it('quantizes q and −q identically and makes the largest component positive', () => {
    const f = createSnapshotFormat(bounds);
    const rng = new Prng(9);
    const out = new Float64Array(4);
    for (let i = 0; i < 500; i++) {
      const q = randomQuat(rng);
      const a = quantizeQ(f, q);
      const b = quantizeQ(f, q.map((c) => -c));
      expect(Array.from(b)).toEqual(Array.from(a));
      dequantizeRotation(f, a[0], a[1], a[2], a[3], out, 0);
      expect(out[a[0]]).toBeGreaterThan(0);
    }
  });

  it('breaks ties between equal largest components by the lowest index, and maps a zero quaternion to identity', () => {
    const f = createSnapshotFormat(bounds);
    const h = Math.SQRT1_2;
    expect(quantizeQ(f, [0, h, 0, h])[0]).toBe(1);
    expect(quantizeQ(f, [0, 0, -h, h])[0]).toBe(2);
    const out = new Float64Array(4);
    const z = quantizeQ(f, [0, 0, 0, 0]);
    dequantizeRotation(f, z[0], z[1], z[2], z[3], out, 0);
    expect(Array.from(out)).toEqual([0, 0, 0, 1]);
  });

  it('quantizes character velocity, yaw, pitch and ground state within their ranges', () => {
    expect(dequantizeVelocity(quantizeVelocity(3.3))).toBeCloseTo(3.3, 2);
    expect(quantizeVelocity(1e9)).toBe(32767);
    expect(quantizeVelocity(-1e9)).toBe(-32767);
    expect(quantizeVelocity(Number.NaN)).toBe(0);
    expect(quantizeYaw(-Math.PI / 2)).toBe(49152);
    expect(quantizeYaw(2 * Math.PI)).toBe(0);
    expect(quantizeYaw(2 * Math.PI - 1e-9)).toBe(0);
    expect(dequantizeYaw(quantizeYaw(1))).toBeCloseTo(1, 4);
    expect(quantizePitch(10)).toBe(16384);
    expect(dequantizePitch(quantizePitch(-0.5))).toBeCloseTo(-0.5, 4);
    expect(['ground', 'steep', 'air', 'unsupported', 'bogus'].map(groundStateCode)).toEqual([0, 1, 2, 3, 3]);
  });
});
