// Tests for scenarios/crowd-arena.ts: one spawn point per player slot, all apart and on the floor inside the walls,
// props resting clear of them, the player cap enforced with a reason, and seed determinism through the Simulation.
import { describe, expect, it } from 'vitest';
import '../../server/physics-node.ts';
import { CROWD_ARENA_MAX_PLAYERS, SPAWN_SPACING_METRES, scenario } from '../../scenarios/crowd-arena.ts';
import { BotScript } from '../../shared/sim/bots.ts';
import { Simulation } from '../../shared/sim/simulation.ts';
import { emptyTickInput } from '../../shared/sim/types.ts';
import { expectParamsValidated } from '../helpers/scenario-checks.ts';
import { ScenarioHarness } from '../helpers/scenario-harness.ts';
import { expectSimulationReplays } from '../helpers/scenario-sim.ts';

describe('crowd-arena', () => {
  it('gives every player slot up to the cap its own spawn point, all apart and inside the walls', async () => {
    const h = await ScenarioHarness.create(scenario);
    try {
      const points = Array.from({ length: CROWD_ARENA_MAX_PLAYERS }, (_, i) => h.instance.spawnPoint(i));
      const wall = h.world.getBody(h.scenarioBodyIds().find((id) => h.world.getBody(id)!.name === 'wall 1')!)!;
      const inner = wall.position().z - 0.25;
      let closest = Infinity;
      const sorted = [...points].sort((a, b) => a.x - b.x);
      for (let i = 0; i < sorted.length; i++) {
        for (let j = i + 1; j < sorted.length && sorted[j].x - sorted[i].x < SPAWN_SPACING_METRES * 1.5; j++) {
          closest = Math.min(closest, Math.hypot(sorted[j].x - sorted[i].x, sorted[j].z - sorted[i].z));
        }
      }
      expect(closest).toBeGreaterThanOrEqual(SPAWN_SPACING_METRES - 1e-9);
      for (const p of points) {
        expect(Math.abs(p.x)).toBeLessThan(inner - 1);
        expect(Math.abs(p.z)).toBeLessThan(inner - 1);
      }
      expect(h.instance.spawnPoint(CROWD_ARENA_MAX_PLAYERS)).toEqual(points[0]);
    } finally {
      h.destroy();
    }
  });

  it('lets its props come to rest on the floor, clear of every spawn point', async () => {
    const h = await ScenarioHarness.create(scenario);
    try {
      expect(h.dynamicBodies()).toHaveLength(scenario.params.props.default);
      h.run(240);
      const props = h.dynamicBodies();
      expect(props).toHaveLength(scenario.params.props.default);
      const points = Array.from({ length: CROWD_ARENA_MAX_PLAYERS }, (_, i) => h.instance.spawnPoint(i));
      let asleep = 0;
      for (const b of props) {
        const p = b.position();
        expect(p.y).toBeGreaterThan(0);
        expect(p.y).toBeLessThan(1);
        const nearest = Math.min(...points.map((s) => Math.hypot(s.x - p.x, s.z - p.z)));
        expect(nearest).toBeGreaterThan(0.35 + 0.6);
        if (!b.isActive()) asleep++;
      }
      expect(asleep).toBe(props.length);
    } finally {
      h.destroy();
    }
  });

  it('rejects unknown and out-of-range parameters with a clear Error', async () => {
    await expectParamsValidated(scenario);
  });

  it('admits its player cap and rejects a join past it, naming the budget', async () => {
    const sim = await Simulation.create({ scenario, seed: 1, params: { props: 0 } });
    try {
      expect(sim.maxPlayers).toBe(CROWD_ARENA_MAX_PLAYERS);
      const joins = Array.from({ length: CROWD_ARENA_MAX_PLAYERS }, (_, i) => ({ playerId: i + 1, name: `p${i + 1}` }));
      sim.step({ ...emptyTickInput(0), joins });
      expect(sim.playerIds()).toHaveLength(CROWD_ARENA_MAX_PLAYERS);
      const extra = { ...emptyTickInput(1), joins: [{ playerId: 9999, name: 'late' }] };
      expect(() => sim.step(extra)).toThrow(/513 players would be in the game, but scenario crowd-arena serves at most 512 \(players\.maxPlayers/);
      expect(sim.tick).toBe(1);
      sim.step({ ...emptyTickInput(1), leaves: [1], joins: [{ playerId: 9999, name: 'swap' }] });
      expect(sim.playerIds()).toHaveLength(CROWD_ARENA_MAX_PLAYERS);
    } finally {
      sim.destroy();
    }
  });

  it('keeps a crowd of walking, jumping bots on the floor inside the walls', async () => {
    const sim = await Simulation.create({ scenario, seed: 3 });
    try {
      const bots = new BotScript({ seed: 3, bots: 64, joinTicks: Array.from({ length: 64 }, () => 0) });
      for (let t = 0; t < 240; t++) sim.step(bots.next());
      const chars = sim.characters();
      expect(chars).toHaveLength(64);
      const inner = (scenario.bounds.max.x - 10) - 0.1;
      for (const c of chars) {
        expect(c.position.y).toBeGreaterThan(-0.1);
        expect(c.position.y).toBeLessThan(2);
        expect(Math.max(Math.abs(c.position.x), Math.abs(c.position.z))).toBeLessThan(inner);
      }
    } finally {
      sim.destroy();
    }
  });

  it('replays bit for bit under bots, across checkpoints, and differs by seed', async () => {
    await expectSimulationReplays(scenario, { props: 64 }, 120, 6);
  });
});
