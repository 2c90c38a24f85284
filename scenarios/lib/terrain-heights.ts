// Height functions for generated terrain: rolling value-noise hills inside a bowl (mesh-terrain, height-field) and a
// noisy mountain (terrain-balls). Pure functions of position and a seed drawn from the scenario's Prng.
import { createValueNoise } from './value-noise.ts';
import type { HeightFn } from './terrain-grid.ts';

/** Shape of the rolling-bowl terrain (all metres). */
export interface BowlTerrainOptions {
  /** Height range of the noise hills. */
  amplitudeMetres: number;
  /** Typical width of one hill. */
  featureMetres: number;
  /** How much the rim rises above the centre, at `radiusMetres`. */
  rimMetres: number;
  radiusMetres: number;
}

/** Noise hills on a paraboloid bowl: things dropped on it roll towards the middle and stay on the terrain. */
export function bowlTerrain(seed: number, opts: BowlTerrainOptions): HeightFn {
  const noise = createValueNoise(seed);
  const invFeature = 1 / opts.featureMetres;
  const invR2 = 1 / (opts.radiusMetres * opts.radiusMetres);
  return (x, z) => (noise.fractal(x * invFeature, z * invFeature, 4) - 0.5) * opts.amplitudeMetres + (x * x + z * z) * invR2 * opts.rimMetres;
}

/** Shape of the mountain terrain (all metres). */
export interface MountainOptions {
  peakMetres: number;
  /** Horizontal distance at which the mountain has fallen to half its height. */
  halfWidthMetres: number;
  /** Height range of the noise roughness on its slopes. */
  roughnessMetres: number;
  featureMetres: number;
}

/** A single peak at the origin, h = peak / (1 + (r / halfWidth)²), roughened by noise: a rational bump, no exp. */
export function mountainTerrain(seed: number, opts: MountainOptions): HeightFn {
  const noise = createValueNoise(seed);
  const invFeature = 1 / opts.featureMetres;
  const invW2 = 1 / (opts.halfWidthMetres * opts.halfWidthMetres);
  return (x, z) => {
    const bump = opts.peakMetres / (1 + (x * x + z * z) * invW2);
    return bump + (noise.fractal(x * invFeature, z * invFeature, 4) - 0.5) * opts.roughnessMetres;
  };
}
