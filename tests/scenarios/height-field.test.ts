// Tests for scenarios/height-field.ts: defaults, parameter checks, a height field covering the terrain, things
// dropped on it coming to rest on the surface, state round trips and seed determinism.
import { describe, expect, it } from 'vitest';
import { scenario } from '../../scenarios/height-field.ts';
import { ScenarioHarness } from '../helpers/scenario-harness.ts';
import { terrainSceneChecks } from '../helpers/terrain-scene-checks.ts';

const SMALL = { samplesPerSide: 24, cellSizeMetres: 0.75, bodyCount: 16, spawnPerTick: 4 };

describe('height-field', () => {
  it('builds with defaults: one static height field of samplesPerSide² samples', async () => {
    const h = await ScenarioHarness.create(scenario);
    try {
      const [terrain] = h.scenarioBodyIds().map((id) => h.world.getBody(id)!);
      expect(terrain.motion).toBe('static');
      const shape = terrain.shape as { kind: string; sampleCount: number; heights: ArrayLike<number> };
      expect(shape.kind).toBe('heightField');
      expect(shape.sampleCount).toBe(scenario.params.samplesPerSide.default);
      expect(shape.heights).toHaveLength(shape.sampleCount * shape.sampleCount);
      expect(h.spawnOptions.get(terrain.id)?.color).toBeDefined();
    } finally {
      h.destroy();
    }
  });

  it('rejects a sample count Jolt cannot block', async () => {
    await expect(ScenarioHarness.create(scenario, { params: { samplesPerSide: 30 } })).rejects.toThrow(/samplesPerSide must be a multiple of 4/);
  });

  it('rejects a terrain wider than its bounds', async () => {
    await expect(ScenarioHarness.create(scenario, { params: { samplesPerSide: 256, cellSizeMetres: 2 } })).rejects.toThrow(/span 510 m; at most 260 m fit the scene bounds/);
  });

  terrainSceneChecks(scenario, SMALL, 8.5);
});
