// Seeded 2-D value noise (lattice hash + smoothstep) and its fractal sum, for generated terrain heights.
// Integer hashing (Math.imul) and arithmetic only, so every engine computes the same heights bit for bit.

/** A seeded 2-D noise field. */
export interface ValueNoise {
  /** Noise at (x, z) in lattice units, in [0, 1). */
  sample(x: number, z: number): number;
  /** Sum of `octaves` octaves (frequency ×2, amplitude ×`gain` each), normalised to [0, 1). */
  fractal(x: number, z: number, octaves: number, gain?: number): number;
}

/** 32-bit hash of a lattice point and the seed (a murmur3-style finaliser). */
export function latticeHash(ix: number, iz: number, seed: number): number {
  let h = Math.imul(ix | 0, 0x27d4eb2d) ^ Math.imul(iz | 0, 0x165667b1) ^ (seed | 0);
  h = Math.imul(h ^ (h >>> 15), 0x85ebca6b);
  h = Math.imul(h ^ (h >>> 13), 0xc2b2ae35);
  return (h ^ (h >>> 16)) >>> 0;
}

function smooth(t: number): number {
  return t * t * (3 - 2 * t);
}

/** A value-noise field for a 32-bit seed (draw it from the scenario's Prng). */
export function createValueNoise(seed: number): ValueNoise {
  if (!Number.isInteger(seed) || seed < 0 || seed > 0xffffffff) throw new Error(`createValueNoise: seed must be a 32-bit unsigned integer, got ${seed}`);
  const s = seed | 0;
  const corner = (ix: number, iz: number): number => latticeHash(ix, iz, s) / 4294967296;
  const sample = (x: number, z: number): number => {
    const x0 = Math.floor(x);
    const z0 = Math.floor(z);
    const tx = smooth(x - x0);
    const tz = smooth(z - z0);
    const a = corner(x0, z0);
    const b = corner(x0 + 1, z0);
    const c = corner(x0, z0 + 1);
    const d = corner(x0 + 1, z0 + 1);
    const top = a + (b - a) * tx;
    const bottom = c + (d - c) * tx;
    return top + (bottom - top) * tz;
  };
  const fractal = (x: number, z: number, octaves: number, gain = 0.5): number => {
    if (!Number.isInteger(octaves) || octaves < 1 || octaves > 12) throw new Error(`ValueNoise.fractal: octaves must be an integer in [1, 12], got ${octaves}`);
    let sum = 0;
    let norm = 0;
    let amplitude = 1;
    let frequency = 1;
    for (let o = 0; o < octaves; o++) {
      // Each octave is offset by a fixed lattice shift so octaves do not share their lattice corners.
      sum += amplitude * sample(x * frequency + o * 17, z * frequency - o * 31);
      norm += amplitude;
      amplitude *= gain;
      frequency *= 2;
    }
    return sum / norm;
  };
  return { sample, fractal };
}
