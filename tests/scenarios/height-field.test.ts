// Tests for scenarios/height-field.ts: defaults, parameter checks, a height field covering the terrain, things
// dropped on it coming to rest on the surface, state round trips and seed determinism.
import { describe, expect, it } from 'vitest';
import { scenario } from '../../scenarios/height-field.ts';
import { expectParamsValidated, expectRestingOnSurface, expectSeedDeterminism } from '../helpers/scenario-checks.ts';
import { ScenarioHarness } from '../helpers/scenario-harness.ts';
import { expectSimulationReplays } from '../helpers/scenario-sim.ts';

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

  it('rejects unknown and out-of-range parameters with a clear Error', async () => {
    await expectParamsValidated(scenario);
  });

  it('answers a downward ray everywhere on the terrain (no holes)', async () => {
    const h = await ScenarioHarness.create(scenario, { params: SMALL });
    try {
      for (let x = -8.5; x <= 8.5; x += 1.25) {
        for (let z = -8.5; z <= 8.5; z += 1.25) expect(h.world.rayDownY(x, 40, z, 80, true), `(${x}, ${z})`).not.toBeNull();
      }
    } finally {
      h.destroy();
    }
  });

  it('drops bodyCount things that come to rest on the terrain surface', async () => {
    const h = await ScenarioHarness.create(scenario, { params: SMALL });
    try {
      h.run(600);
      expect(h.dynamicBodies()).toHaveLength(SMALL.bodyCount);
      expectRestingOnSurface(h, 1.2, 0.3);
    } finally {
      h.destroy();
    }
  });

  it('places spawn points on the terrain', async () => {
    const h = await ScenarioHarness.create(scenario, { params: SMALL });
    try {
      for (let i = 0; i < 8; i++) {
        const s = h.instance.spawnPoint(i);
        const ground = h.world.rayDownY(s.x, s.y + 5, s.z, 20, true)!;
        expect(s.y - ground).toBeGreaterThanOrEqual(0);
        expect(s.y - ground).toBeLessThan(0.6);
      }
    } finally {
      h.destroy();
    }
  });

  it('round-trips its scenario state and rejects a bad one', async () => {
    const h = await ScenarioHarness.create(scenario, { params: SMALL });
    try {
      h.run(2);
      expect(h.instance.saveState!()).toEqual([8]);
      h.instance.restoreState!([3]);
      expect(h.instance.saveState!()).toEqual([3]);
      expect(() => h.instance.restoreState!([-1])).toThrow(/height-field: bad saved state/);
    } finally {
      h.destroy();
    }
  });

  it('gives identical bodies for one seed and different ones for another', async () => {
    await expectSeedDeterminism(scenario, SMALL, 90);
  });
  it('runs deterministically through the Simulation with bots, across checkpoint rollbacks', async () => {
    await expectSimulationReplays(scenario, SMALL, 120, 2);
  });
});
