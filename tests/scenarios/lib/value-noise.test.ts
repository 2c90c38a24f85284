// Tests for scenarios/lib/value-noise.ts: range, lattice values, continuity, seed dependence and argument checks.
import { describe, expect, it } from 'vitest';
import { createValueNoise, latticeHash } from '../../../scenarios/lib/value-noise.ts';

describe('value-noise', () => {
  it('stays in [0, 1) and returns the lattice value at integer points', () => {
    const n = createValueNoise(1234);
    for (let i = 0; i < 500; i++) {
      const x = (i * 0.37) % 23;
      const z = (i * 0.91) % 17;
      const v = n.sample(x, z);
      expect(v).toBeGreaterThanOrEqual(0);
      expect(v).toBeLessThan(1);
      const f = n.fractal(x, z, 5);
      expect(f).toBeGreaterThanOrEqual(0);
      expect(f).toBeLessThan(1);
    }
    expect(n.sample(3, -4)).toBe(latticeHash(3, -4, 1234) / 4294967296);
  });

  it('varies continuously between lattice points', () => {
    const n = createValueNoise(99);
    let worst = 0;
    for (let x = -5; x < 5; x += 0.01) worst = Math.max(worst, Math.abs(n.sample(x + 0.01, 0.5) - n.sample(x, 0.5)));
    expect(worst).toBeLessThan(0.03);
  });

  it('gives the same field for one seed and another field for another seed', () => {
    const a = createValueNoise(7);
    const b = createValueNoise(7);
    const c = createValueNoise(8);
    const pts = Array.from({ length: 50 }, (_, i) => [i * 0.73, -i * 0.41] as const);
    expect(pts.map(([x, z]) => a.fractal(x, z, 4))).toEqual(pts.map(([x, z]) => b.fractal(x, z, 4)));
    expect(pts.filter(([x, z]) => a.fractal(x, z, 4) !== c.fractal(x, z, 4)).length).toBeGreaterThan(45);
  });

  it('rejects bad seeds and octave counts with clear Errors', () => {
    expect(() => createValueNoise(-1)).toThrow(/seed must be a 32-bit unsigned integer/);
    expect(() => createValueNoise(1.5)).toThrow(/seed must be a 32-bit unsigned integer/);
    expect(() => createValueNoise(1).fractal(0, 0, 0)).toThrow(/octaves must be an integer in \[1, 12\]/);
  });
});
