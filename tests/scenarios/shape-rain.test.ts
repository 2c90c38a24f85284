// Tests for scenarios/shape-rain.ts: defaults, parameter checks, the rain filling up and settling inside the walls,
// re-dropping with recycleAfterTicks, scenario state round trips and seed determinism (through the test harness).
import { describe, expect, it } from 'vitest';
import { scenario } from '../../scenarios/shape-rain.ts';
import { expectParamsValidated, expectSeedDeterminism } from '../helpers/scenario-checks.ts';
import { ScenarioHarness } from '../helpers/scenario-harness.ts';
import { expectSimulationReplays } from '../helpers/scenario-sim.ts';

const SMALL = { count: 60, spawnPerTick: 6, areaMetres: 8, dropHeightMetres: 4 };

describe('shape-rain', () => {
  it('builds with defaults: a walled ground, then drops spawnPerTick coloured shapes per tick', async () => {
    const h = await ScenarioHarness.create(scenario);
    try {
      const statics = h.scenarioBodyIds().map((id) => h.world.getBody(id)!);
      expect(statics).toHaveLength(5);
      expect(statics.every((b) => b.motion === 'static')).toBe(true);
      h.run(3);
      const dynamic = h.dynamicBodies();
      expect(dynamic).toHaveLength(3 * scenario.params.spawnPerTick.default);
      expect(dynamic.every((b) => h.spawnOptions.get(b.id)?.color !== undefined)).toBe(true);
      expect(h.events.filter((e) => e.type === 'bodySpawned')).toHaveLength(dynamic.length);
    } finally {
      h.destroy();
    }
  });

  it('rejects unknown and out-of-range parameters with a clear Error', async () => {
    await expectParamsValidated(scenario);
  });

  it('stops at count bodies and mixes boxes, spheres, capsules and hulls', async () => {
    const h = await ScenarioHarness.create(scenario, { params: SMALL });
    try {
      h.run(20);
      const dynamic = h.dynamicBodies();
      expect(dynamic).toHaveLength(SMALL.count);
      expect(new Set(dynamic.map((b) => b.shape!.kind))).toEqual(new Set(['box', 'sphere', 'capsule', 'convexHull']));
    } finally {
      h.destroy();
    }
  });

  it('lets the shapes come to rest on the ground inside the walls', async () => {
    const h = await ScenarioHarness.create(scenario, { params: SMALL });
    try {
      h.run(420);
      const dynamic = h.dynamicBodies();
      expect(dynamic).toHaveLength(SMALL.count);
      const wall = SMALL.areaMetres / 2 + 3;
      const speeds: number[] = [];
      for (const b of dynamic) {
        const p = b.position();
        const v = b.linearVelocity();
        expect(p.y).toBeGreaterThan(0);
        expect(p.y).toBeLessThan(3);
        expect(Math.abs(p.x)).toBeLessThan(wall);
        expect(Math.abs(p.z)).toBeLessThan(wall);
        speeds.push(Math.sqrt(v.x * v.x + v.y * v.y + v.z * v.z));
      }
      expect(Math.max(...speeds)).toBeLessThan(0.5);
      expect(speeds.filter((s) => s < 0.1).length).toBeGreaterThanOrEqual(0.85 * SMALL.count);
      expect(dynamic.filter((b) => !b.isActive()).length).toBeGreaterThan(SMALL.count / 2);
    } finally {
      h.destroy();
    }
  });

  it('re-drops the oldest shape once it has lived recycleAfterTicks', async () => {
    const h = await ScenarioHarness.create(scenario, { params: { ...SMALL, count: 12, recycleAfterTicks: 30 } });
    try {
      h.run(2);
      const first = h.dynamicBodies().map((b) => b.id);
      h.run(60);
      const now = h.dynamicBodies().map((b) => b.id);
      expect(now).toHaveLength(12);
      expect(now.some((id) => first.includes(id))).toBe(false);
      expect(h.events.filter((e) => e.type === 'bodyRemoved').length).toBeGreaterThanOrEqual(12);
    } finally {
      h.destroy();
    }
  });

  it('forgets shapes that left the bounds, keeping the drop order of the rest, and drops new ones in their place', async () => {
    const h = await ScenarioHarness.create(scenario, { params: { ...SMALL, count: 12 } });
    try {
      h.run(2);
      const listed = (): number[] => h.instance.saveState!().slice(1).filter((_, i) => i % 2 === 0);
      const before = listed();
      expect(before).toHaveLength(12);
      const [first, , third] = before;
      for (const id of [third, first]) h.world.setPosition(id, { x: 0, y: -1000, z: 0 });
      h.run(2); // removed at the end of the first tick, forgotten and replaced by the scenario in the second
      expect(listed().slice(0, 10)).toEqual(before.filter((id) => id !== first && id !== third));
      expect(listed()).toHaveLength(12);
      expect(h.events.filter((e) => e.type === 'bodyRemoved').map((e) => (e as { bodyId: number }).bodyId).sort()).toEqual([first, third].sort());
    } finally {
      h.destroy();
    }
  });

  it('round-trips its scenario state', async () => {
    const h = await ScenarioHarness.create(scenario, { params: SMALL });
    try {
      h.run(4);
      const saved = h.instance.saveState!();
      expect(saved.length).toBe(1 + 2 * 24);
      h.instance.restoreState!(saved);
      expect(h.instance.saveState!()).toEqual(saved);
      expect(() => h.instance.restoreState!([1, 2])).toThrow(/shape-rain: bad saved state/);
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
