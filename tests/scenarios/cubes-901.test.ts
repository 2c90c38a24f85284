// Tests for scenarios/cubes-901.ts: the 30 × 30 field plus the big cube, parameter checks, the field coming to
// rest, the first player's input rolling the big cube through the field, its respawn, and seed determinism.
import { describe, expect, it } from 'vitest';
import { scenario } from '../../scenarios/cubes-901.ts';
import { expectParamsValidated, expectSeedDeterminism } from '../helpers/scenario-checks.ts';
import { Simulation } from '../../shared/sim/simulation.ts';
import { ScenarioHarness } from '../helpers/scenario-harness.ts';
import { expectSimulationReplays } from '../helpers/scenario-sim.ts';

const SMALL = { side: 8 };

function bigCube(h: ScenarioHarness) {
  return h.dynamicBodies().find((b) => b.name === 'big cube')!;
}

describe('cubes-901', () => {
  it('builds with defaults: 900 small cubes in a 30 × 30 grid plus one big cube', async () => {
    const h = await ScenarioHarness.create(scenario);
    try {
      const dynamic = h.dynamicBodies();
      expect(dynamic).toHaveLength(901);
      const small = dynamic.filter((b) => b.name?.startsWith('cube '));
      expect(small).toHaveLength(900);
      expect(new Set(small.map((b) => b.position().x.toFixed(3))).size).toBe(30);
      expect(new Set(small.map((b) => b.position().z.toFixed(3))).size).toBe(30);
      expect(bigCube(h).shape).toEqual({ kind: 'box', halfExtents: { x: 1, y: 1, z: 1 } });
    } finally {
      h.destroy();
    }
  });

  it('rejects unknown and out-of-range parameters, overlapping cubes and fields too big for the ground', async () => {
    await expectParamsValidated(scenario);
    await expect(ScenarioHarness.create(scenario, { params: { cubeSizeMetres: 0.8, spacingMetres: 0.5 } })).rejects.toThrow(/spacingMetres \(0.5\) must be at least cubeSizeMetres/);
    await expect(ScenarioHarness.create(scenario, { params: { side: 60, spacingMetres: 3 } })).rejects.toThrow(/does not fit/);
  });

  it('lets the field settle and fall asleep when nobody drives', async () => {
    const h = await ScenarioHarness.create(scenario, { params: SMALL });
    try {
      h.run(120);
      expect(h.dynamicBodies().every((b) => !b.isActive())).toBe(true);
    } finally {
      h.destroy();
    }
  });

  it('rolls the big cube through the field with the first player’s move axes', async () => {
    const h = await ScenarioHarness.create(scenario, { params: SMALL });
    try {
      const small = h.dynamicBodies().filter((b) => b.name?.startsWith('cube '));
      const start = new Map(small.map((b) => [b.id, b.position()]));
      const big = bigCube(h);
      const z0 = big.position().z;
      h.join(1);
      h.join(2);
      h.setInput(2, { moveZ: -127 }); // a later player's input does not drive
      h.run(30);
      expect(Math.abs(big.position().z - z0)).toBeLessThan(0.01);
      h.setInput(1, { moveZ: 127 }); // forward at yaw 0 is -z, into the field
      h.run(300);
      const z = big.position().z;
      expect(z).toBeLessThan(-4);
      const moved = small.filter((b) => {
        const p = b.position();
        const s = start.get(b.id)!;
        return (p.x - s.x) * (p.x - s.x) + (p.z - s.z) * (p.z - s.z) > 0.25;
      });
      expect(moved.length).toBeGreaterThanOrEqual(6);
      // Rolling, not sliding: it has turned over.
      expect(Math.abs(big.rotation().w)).toBeLessThan(0.99);
    } finally {
      h.destroy();
    }
  });

  it('steers with yaw: strafing right at yaw 0 rolls towards +x', async () => {
    const h = await ScenarioHarness.create(scenario, { params: SMALL });
    try {
      const big = bigCube(h);
      const x0 = big.position().x;
      h.join(1);
      h.setInput(1, { moveX: 127 });
      h.run(120);
      expect(big.position().x - x0).toBeGreaterThan(3);
    } finally {
      h.destroy();
    }
  });

  it('puts a new big cube at the start when the old one has left the world', async () => {
    const h = await ScenarioHarness.create(scenario, { params: SMALL });
    try {
      const old = bigCube(h);
      h.world.setPosition(old, { x: 0, y: -20, z: 0 });
      h.run(2);
      const fresh = bigCube(h);
      expect(fresh.id).not.toBe(old.id);
      expect(fresh.position().y).toBeCloseTo(1, 1);
      expect(h.instance.saveState!()).toEqual([fresh.id]);
    } finally {
      h.destroy();
    }
  });

  it('gives identical bodies for one seed and different ones for another', async () => {
    // The field is not random, so the seed reaches the run through a seeded drive: the first player's stick.
    const drive = (h: ScenarioHarness, tick: number): void => {
      if (tick === -1) h.join(1);
      if (tick >= 0 && tick % 20 === 0) h.setInput(1, { moveX: h.rng.int(-127, 127), moveZ: h.rng.int(0, 127) });
    };
    await expectSeedDeterminism(scenario, SMALL, 120, drive);
  });
  it('rolls the big cube with the input of the lowest player id in the Simulation', async () => {
    const sim = await Simulation.create({ scenario, params: SMALL });
    try {
      const bigId = sim.descriptors().find((d) => d.motion === 'dynamic' && d.shape.kind === 'box' && (d.shape as { halfExtents: { x: number } }).halfExtents.x === 1)!.id;
      const z0 = sim.world.getBody(bigId)!.position().z;
      const cmd = (moveZ: number) => ({ moveX: 0, moveZ, yaw: 0, pitch: 0, buttons: 0 });
      for (let t = 0; t < 240; t++) {
        sim.step({
          tick: t,
          leaves: [],
          joins: t === 0 ? [{ playerId: 7, name: 'driver' }, { playerId: 9, name: 'passenger' }] : [],
          commands: [{ playerId: 7, input: cmd(127) }, { playerId: 9, input: cmd(-127) }],
        });
      }
      expect(sim.world.getBody(bigId)!.position().z - z0).toBeLessThan(-10);
    } finally {
      sim.destroy();
    }
  });

  it('runs deterministically through the Simulation with bots, across checkpoint rollbacks', async () => {
    await expectSimulationReplays(scenario, SMALL, 120, 2);
  });
});
