// Tests for scenarios/pendulum-chain.ts: defaults, parameter checks, point links keeping every link length while the
// chains swing, pins knocked over, and seed determinism.
import { describe, expect, it } from 'vitest';
import { scenario } from '../../scenarios/pendulum-chain.ts';
import { expectParamsValidated, expectSeedDeterminism } from '../helpers/scenario-checks.ts';
import { ScenarioHarness } from '../helpers/scenario-harness.ts';
import { expectSimulationReplays } from '../helpers/scenario-sim.ts';

const SMALL = { chains: 2, links: 6, linkLengthMetres: 0.5, sphereRadiusMetres: 0.15, pinsPerChain: 3 };

function chainBodies(h: ScenarioHarness, chain: number): { anchor: number; links: number[] } {
  const ids = h.scenarioBodyIds().map((id) => h.world.getBody(id)!);
  const anchor = ids.find((b) => b.name === `anchor ${chain}`)!.id;
  const links = ids.filter((b) => b.name?.startsWith(`chain ${chain} link `)).map((b) => b.id);
  return { anchor, links };
}

function distance(h: ScenarioHarness, a: number, b: number): number {
  const p = h.world.getBody(a)!.position();
  const q = h.world.getBody(b)!.position();
  return Math.sqrt((p.x - q.x) * (p.x - q.x) + (p.y - q.y) * (p.y - q.y) + (p.z - q.z) * (p.z - q.z));
}

describe('pendulum-chain', () => {
  it('builds with defaults: chains × links spheres held by as many point links', async () => {
    const h = await ScenarioHarness.create(scenario);
    try {
      const { chains, links } = { chains: scenario.params.chains.default, links: scenario.params.links.default };
      expect(h.world.constraintCount).toBe(chains * links);
      expect(h.dynamicBodies().filter((b) => b.shape?.kind === 'sphere')).toHaveLength(chains * links);
      expect(h.dynamicBodies().filter((b) => b.name?.startsWith('pin '))).toHaveLength(chains * scenario.params.pinsPerChain.default);
    } finally {
      h.destroy();
    }
  });

  it('rejects unknown and out-of-range parameters, and spheres too big for their links', async () => {
    await expectParamsValidated(scenario);
    await expect(ScenarioHarness.create(scenario, { params: { linkLengthMetres: 0.3, sphereRadiusMetres: 0.2 } })).rejects.toThrow(/must be under half of linkLengthMetres/);
  });

  it('keeps every link length while the chains swing through the vertical', async () => {
    const h = await ScenarioHarness.create(scenario, { params: SMALL });
    try {
      const chains = [0, 1].map((c) => chainBodies(h, c));
      const L = SMALL.linkLengthMetres;
      let worst = 0;
      const startZ = chains.map((c) => h.world.getBody(c.links[c.links.length - 1])!.position().z);
      const crossed = [false, false];
      for (let t = 0; t < 240; t++) {
        h.step();
        chains.forEach((c, i) => {
          const pairs = [c.anchor, ...c.links];
          for (let k = 1; k < pairs.length; k++) worst = Math.max(worst, Math.abs(distance(h, pairs[k - 1], pairs[k]) - L));
          const z = h.world.getBody(c.links[c.links.length - 1])!.position().z;
          if (Math.sign(z) !== Math.sign(startZ[i])) crossed[i] = true;
        });
      }
      expect(worst).toBeLessThan(0.02 * L);
      expect(crossed).toEqual([true, true]);
    } finally {
      h.destroy();
    }
  });

  it('knocks pins over with the swinging chains', async () => {
    const h = await ScenarioHarness.create(scenario, { params: SMALL });
    try {
      const pins = h.dynamicBodies().filter((b) => b.name?.startsWith('pin '));
      expect(pins.length).toBeGreaterThan(0);
      h.run(240);
      // A pin standing upright keeps its rotation's w near ±1; a knocked one is tilted.
      const tilted = pins.filter((b) => Math.abs(b.rotation().w) < 0.95);
      expect(tilted.length).toBeGreaterThan(0);
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
