// The behaviour checks shared by the terrain scenes (height-field, mesh-terrain): no holes under a downward ray,
// dropped things resting on the surface, spawn points on the ground, saved state, seeds and Simulation replays.
import { expect, it } from 'vitest';
import type { ScenarioDefinition } from '../../shared/sim/scenario.ts';
import { expectParamsValidated, expectRestingOnSurface, expectSeedDeterminism } from './scenario-checks.ts';
import { ScenarioHarness } from './scenario-harness.ts';
import { expectSimulationReplays } from './scenario-sim.ts';

/** Registers the shared terrain-scene tests for `scenario` built with `small` params (which set bodyCount). */
export function terrainSceneChecks(scenario: ScenarioDefinition, small: Readonly<Record<string, number>> & { bodyCount: number }, halfMetres: number): void {
  const withHarness = async (run: (h: ScenarioHarness) => void): Promise<void> => {
    const h = await ScenarioHarness.create(scenario, { params: small });
    try {
      run(h);
    } finally {
      h.destroy();
    }
  };

  it('rejects unknown and out-of-range parameters with a clear Error', async () => {
    await expectParamsValidated(scenario);
  });

  it('answers a downward ray everywhere on the terrain (no holes, faces up)', async () => {
    await withHarness((h) => {
      for (let x = -halfMetres; x <= halfMetres; x += 1.25) {
        for (let z = -halfMetres; z <= halfMetres; z += 1.25) expect(h.world.rayDownY(x, 40, z, 80, true), `(${x}, ${z})`).not.toBeNull();
      }
    });
  });

  it('drops bodyCount things that come to rest on the terrain surface', async () => {
    await withHarness((h) => {
      h.run(600);
      expect(h.dynamicBodies()).toHaveLength(small.bodyCount);
      expectRestingOnSurface(h, 1.2, 0.3);
    });
  });

  it('places spawn points on the terrain', async () => {
    await withHarness((h) => {
      for (let i = 0; i < 8; i++) {
        const s = h.instance.spawnPoint(i);
        const ground = h.world.rayDownY(s.x, s.y + 5, s.z, 20, true)!;
        expect(s.y - ground).toBeGreaterThanOrEqual(0);
        expect(s.y - ground).toBeLessThan(0.6);
      }
    });
  });

  it('round-trips its scenario state and rejects a bad one', async () => {
    await withHarness((h) => {
      h.run(2);
      expect(h.instance.saveState!()).toEqual([2 * small.spawnPerTick]);
      h.instance.restoreState!([3]);
      expect(h.instance.saveState!()).toEqual([3]);
      expect(() => h.instance.restoreState!([-1])).toThrow(new RegExp(`${scenario.name}: bad saved state`));
    });
  });

  it('gives identical bodies for one seed and different ones for another', async () => {
    await expectSeedDeterminism(scenario, small, 90);
  });

  it('runs deterministically through the Simulation with bots, across checkpoint rollbacks', async () => {
    await expectSimulationReplays(scenario, small, 120, 2);
  });
}
