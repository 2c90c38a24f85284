// Tests for scenarios/mesh-terrain.ts: defaults, parameter checks, a watertight upward-facing terrain mesh, things
// dropped on it coming to rest on the surface, state round trips and seed determinism.
import { describe, expect, it } from 'vitest';
import { scenario } from '../../scenarios/mesh-terrain.ts';
import { ScenarioHarness } from '../helpers/scenario-harness.ts';
import { terrainSceneChecks } from '../helpers/terrain-scene-checks.ts';

const SMALL = { cells: 16, bodyCount: 16, spawnPerTick: 4 };

describe('mesh-terrain', () => {
  it('builds with defaults: one static mesh of cells² × 2 triangles', async () => {
    const h = await ScenarioHarness.create(scenario);
    try {
      const [terrain] = h.scenarioBodyIds().map((id) => h.world.getBody(id)!);
      expect(terrain.motion).toBe('static');
      expect(terrain.shape?.kind).toBe('mesh');
      const cells = scenario.params.cells.default;
      expect((terrain.shape as { indices: ArrayLike<number> }).indices.length).toBe(cells * cells * 6);
      expect(h.spawnOptions.get(terrain.id)?.color).toBeDefined();
    } finally {
      h.destroy();
    }
  });

  terrainSceneChecks(scenario, SMALL, 7.5);
});
