// Tests for scenarios/convex-hulls.ts: defaults, parameter checks (including minPoints <= maxPoints), hull point
// counts and styles, hulls settling on the ground, state round trips and seed determinism.
import { describe, expect, it } from 'vitest';
import { scenario } from '../../scenarios/convex-hulls.ts';
import { expectParamsValidated, expectRestingOnSurface, expectSeedDeterminism } from '../helpers/scenario-checks.ts';
import { ScenarioHarness } from '../helpers/scenario-harness.ts';
import { expectSimulationReplays } from '../helpers/scenario-sim.ts';

const SMALL = { count: 40, spawnPerTick: 5, areaMetres: 8, minPoints: 5, maxPoints: 12 };

describe('convex-hulls', () => {
  it('builds with defaults: a walled ground, then spawnPerTick hulls per tick', async () => {
    const h = await ScenarioHarness.create(scenario);
    try {
      expect(h.scenarioBodyIds()).toHaveLength(5);
      h.run(2);
      const hulls = h.dynamicBodies();
      expect(hulls).toHaveLength(2 * scenario.params.spawnPerTick.default);
      expect(hulls.every((b) => b.shape?.kind === 'convexHull')).toBe(true);
    } finally {
      h.destroy();
    }
  });

  it('rejects unknown and out-of-range parameters with a clear Error', async () => {
    await expectParamsValidated(scenario);
    await expect(ScenarioHarness.create(scenario, { params: { minPoints: 20, maxPoints: 10 } })).rejects.toThrow(/minPoints \(20\) must not exceed maxPoints \(10\)/);
  });

  it('builds each hull from a cloud of minPoints..maxPoints points in four styles', async () => {
    const h = await ScenarioHarness.create(scenario, { params: SMALL });
    try {
      h.run(8);
      const hulls = h.dynamicBodies();
      expect(hulls).toHaveLength(SMALL.count);
      for (const b of hulls) {
        const n = (b.shape as { points: ArrayLike<number> }).points.length / 3;
        expect(n).toBeGreaterThanOrEqual(SMALL.minPoints);
        expect(n).toBeLessThanOrEqual(SMALL.maxPoints);
      }
      expect(new Set(hulls.map((b) => b.name!.split(' ')[0]))).toEqual(new Set(['rock', 'shard', 'slab', 'crystal']));
    } finally {
      h.destroy();
    }
  });

  it('lets the hulls come to rest on the ground', async () => {
    const h = await ScenarioHarness.create(scenario, { params: SMALL });
    try {
      h.run(360);
      expectRestingOnSurface(h, 2, 0.1);
      expect(h.dynamicBodies().filter((b) => !b.isActive()).length).toBeGreaterThan(SMALL.count / 2);
    } finally {
      h.destroy();
    }
  });

  it('round-trips its scenario state', async () => {
    const h = await ScenarioHarness.create(scenario, { params: SMALL });
    try {
      h.run(3);
      expect(h.instance.saveState!()).toEqual([15]);
      h.instance.restoreState!([2]);
      expect(h.instance.saveState!()).toEqual([2]);
      expect(() => h.instance.restoreState!([1.5])).toThrow(/convex-hulls: bad saved state/);
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
