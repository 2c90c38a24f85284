// height-field: a static Jolt height field (seeded value-noise hills in a bowl, the memory-light terrain path) with
// balls, boxes, capsules and hulls dropped onto it a few per tick; they roll into the hollows and settle.
import type { ScenarioContext, ScenarioDefinition, ScenarioInstance } from '../shared/sim/scenario.ts';
import { Palette } from './lib/palette.ts';
import { terrainDropInstance } from './lib/terrain-drops.ts';
import { heightSamples } from './lib/terrain-grid.ts';
import { bowlTerrain } from './lib/terrain-heights.ts';

/** Largest half-width of the terrain (m): the bounds (±140 m) with room for things rolling off its rim. */
const TERRAIN_HALF_LIMIT_METRES = 130;

/** A height-field terrain with things rolling on it. */
export const scenario: ScenarioDefinition = {
  name: 'height-field',
  description: 'A generated height-field terrain (noise hills in a bowl); balls and shapes drop onto it and roll into the hollows.',
  params: {
    samplesPerSide: { default: 64, min: 8, max: 256, integer: true, description: 'height samples per side (a multiple of 4; samples − 1 cells)' },
    cellSizeMetres: { default: 0.75, min: 0.25, max: 2, description: 'distance between two samples (m)' },
    amplitudeMetres: { default: 3, min: 0, max: 12, description: 'height range of the hills (m)' },
    bodyCount: { default: 80, min: 0, max: 2000, integer: true, description: 'things dropped onto the terrain' },
    spawnPerTick: { default: 2, min: 1, max: 100, integer: true, description: 'things dropped per tick until bodyCount is reached' },
  },
  bounds: { min: { x: -140, y: -30, z: -140 }, max: { x: 140, y: 90, z: 140 } },
  golden: { ticks: 240, bots: 1 },
  world: { maxBodyPairs: 32768, maxContactConstraints: 16384 },
  build(ctx: ScenarioContext): ScenarioInstance {
    const p = ctx.params;
    const n = p.samplesPerSide;
    if (n % 4 !== 0) throw new Error(`scenario height-field: parameter samplesPerSide must be a multiple of 4 (Jolt's height-field blocks), got ${n}`);
    const extent = ((n - 1) * p.cellSizeMetres) / 2;
    if (extent > TERRAIN_HALF_LIMIT_METRES) {
      throw new Error(`scenario height-field: ${n} samples ${p.cellSizeMetres} m apart span ${2 * extent} m; at most ${2 * TERRAIN_HALF_LIMIT_METRES} m fit the scene bounds`);
    }
    const heightAt = bowlTerrain(ctx.rng.nextU32(), {
      amplitudeMetres: p.amplitudeMetres,
      featureMetres: 6,
      rimMetres: Math.max(2, extent * 0.25),
      radiusMetres: extent,
    });
    const heights = heightSamples(heightAt, -extent, -extent, n, p.cellSizeMetres);
    ctx.spawn({ kind: 'heightField', heights, sampleCount: n, cellSize: p.cellSizeMetres, originXz: { x: -extent, z: -extent } }, { x: 0, y: 0, z: 0 }, null, {
      motion: 'static',
      friction: 0.7,
      color: Palette.terrain,
      name: 'terrain',
    });
    return terrainDropInstance('height-field', heightAt, extent * 0.7, 0.5, p.spawnPerTick, p.bodyCount);
  },
};
