// mesh-terrain: one static triangle-mesh terrain (seeded value-noise hills in a bowl) with balls, boxes, capsules
// and hulls dropped onto it a few per tick; they roll into the hollows and settle.
import type { ScenarioContext, ScenarioDefinition, ScenarioInstance } from '../shared/sim/scenario.ts';
import { Palette } from './lib/palette.ts';
import { terrainDropInstance } from './lib/terrain-drops.ts';
import { gridMesh, meshHeightAt } from './lib/terrain-grid.ts';
import { bowlTerrain } from './lib/terrain-heights.ts';

/** A triangle-mesh terrain with things rolling on it. */
export const scenario: ScenarioDefinition = {
  name: 'mesh-terrain',
  description: 'A generated triangle-mesh terrain (noise hills in a bowl); balls and shapes drop onto it and roll into the hollows.',
  params: {
    cells: { default: 48, min: 4, max: 128, integer: true, description: 'terrain cells per side (2 triangles each)' },
    cellSizeMetres: { default: 1, min: 0.25, max: 2, description: 'size of one terrain cell (m)' },
    amplitudeMetres: { default: 3, min: 0, max: 12, description: 'height range of the hills (m)' },
    bodyCount: { default: 80, min: 0, max: 2000, integer: true, description: 'things dropped onto the terrain' },
    spawnPerTick: { default: 2, min: 1, max: 100, integer: true, description: 'things dropped per tick until bodyCount is reached' },
  },
  bounds: { min: { x: -140, y: -30, z: -140 }, max: { x: 140, y: 90, z: 140 } },
  golden: { ticks: 240, bots: 1 },
  world: { maxBodyPairs: 32768, maxContactConstraints: 16384 },
  build(ctx: ScenarioContext): ScenarioInstance {
    const p = ctx.params;
    const half = Math.floor(p.cells / 2);
    const extent = half * p.cellSizeMetres;
    const heightAt = bowlTerrain(ctx.rng.nextU32(), {
      amplitudeMetres: p.amplitudeMetres,
      featureMetres: 6,
      rimMetres: Math.max(2, extent * 0.25),
      radiusMetres: extent,
    });
    const mesh = gridMesh(heightAt, -half, -half, p.cells, p.cells, p.cellSizeMetres);
    ctx.spawn({ kind: 'mesh', positions: mesh.positions, indices: mesh.indices }, { x: 0, y: 0, z: 0 }, null, {
      motion: 'static',
      friction: 0.7,
      color: Palette.terrain,
      name: 'terrain',
    });
    const surface = (x: number, z: number): number => meshHeightAt(heightAt, x, z, p.cellSizeMetres);
    return terrainDropInstance('mesh-terrain', surface, extent * 0.7, 0.3, p.spawnPerTick, p.bodyCount);
  },
};
