// Tests of players: joining at the scenario's spawn point, walking along the yaw, jumping, riding a moving platform,
// being put back at the spawn point after leaving the bounds, and the player rules' validation.
import { describe, expect, it } from 'vitest';
import { Button, quantizeInput } from '../../../shared/sim/input.ts';
import { resolvePlayerRules } from '../../../shared/sim/players.ts';
import type { ScenarioDefinition } from '../../../shared/sim/scenario.ts';
import type { Simulation } from '../../../shared/sim/simulation.ts';
import { IDLE, makeSim, record } from './helpers/sim-helpers.ts';
import { testArena } from './helpers/test-scenarios.ts';

function hold(sim: Simulation, ticks: number, input: typeof IDLE, playerId = 1): void {
  for (let i = 0; i < ticks; i++) sim.step(record(sim.tick, { commands: [{ playerId, input }] }));
}

async function withPlayer(def: ScenarioDefinition = testArena): Promise<Simulation> {
  const sim = await makeSim(def, { spawnEvery: 0, boxes: 0 });
  sim.step(record(0, { joins: [{ playerId: 1, name: 'p' }] }));
  return sim;
}

/** A platform sliding +x at 2 m/s from tick 30 on, with its top at y = 0.2 under the first spawn point. */
const platformScene: ScenarioDefinition = {
  ...testArena,
  name: 'platform',
  build(ctx) {
    ctx.spawn({ kind: 'box', halfExtents: { x: 20, y: 0.5, z: 20 } }, { x: 0, y: -2, z: 0 }, null, { motion: 'static' });
    const id = ctx.spawn({ kind: 'box', halfExtents: { x: 2, y: 0.1, z: 2 } }, { x: 0, y: 0.1, z: 0 }, null, { motion: 'kinematic' }).id;
    let x = 0;
    return {
      spawnPoint: () => ({ x: 0, y: 0.25, z: 0 }),
      onTick(c) {
        if (c.tick >= 30) {
          x += 2 / 60;
          c.world.moveKinematic(id, { x, y: 0.1, z: 0 }, null);
        }
      },
      saveState: () => [x],
      restoreState: (s) => void (x = s[0]),
    };
  },
};

describe('players', () => {
  it("puts a joining player's feet at the scenario spawn point for its join index", async () => {
    const sim = await makeSim(testArena, { spawnEvery: 0 });
    sim.step(record(0, { joins: [{ playerId: 10, name: 'a' }, { playerId: 11, name: 'b' }] }));
    sim.step(record(1, { leaves: [10] }));
    sim.step(record(2, { joins: [{ playerId: 10, name: 'a again' }] }));
    const byId = new Map(sim.characters().map((c) => [c.playerId, c]));
    expect(byId.get(11)!.position.x).toBeCloseTo(1.5, 1);
    expect(byId.get(10)!.position.x).toBeCloseTo(3, 1);
    expect(byId.get(10)!.position.z).toBeCloseTo(4, 1);
    sim.destroy();
  });

  it('walks along the yaw at the walk speed and faster when sprinting', async () => {
    const sim = await withPlayer();
    const start = sim.characters()[0].position;
    hold(sim, 60, quantizeInput(0, 1, Math.PI / 2, 0, 0));
    const walked = sim.characters()[0].position;
    expect(walked.x - start.x).toBeCloseTo(-4, 0);
    expect(walked.z - start.z).toBeCloseTo(0, 1);
    hold(sim, 60, quantizeInput(0, 1, -Math.PI / 2, 0, Button.Sprint));
    expect(sim.characters()[0].position.x - walked.x).toBeCloseTo(7.2, 0);
    sim.destroy();
  });

  it('jumps when Jump is held on the ground and lands again', async () => {
    const sim = await withPlayer();
    hold(sim, 10, IDLE);
    hold(sim, 1, { ...IDLE, buttons: Button.Jump });
    let peak = 0;
    for (let i = 0; i < 20; i++) {
      hold(sim, 1, IDLE);
      peak = Math.max(peak, sim.characters()[0].position.y);
    }
    expect(peak).toBeGreaterThan(1);
    expect(peak).toBeLessThan(1.6);
    hold(sim, 60, IDLE);
    expect(sim.characters()[0].groundState).toBe('ground');
    expect(sim.characters()[0].position.y).toBeCloseTo(0, 1);
    sim.destroy();
  });

  it('rides a moving platform it stands on', async () => {
    const sim = await withPlayer(platformScene);
    hold(sim, 150, IDLE);
    const c = sim.characters()[0];
    const platform = sim.world.getBody(2)!.position();
    expect(platform.x).toBeGreaterThan(3.5);
    expect(c.position.x).toBeCloseTo(platform.x, 0);
    expect(c.groundState).toBe('ground');
    sim.destroy();
  });

  it('puts a character that falls out of the bounds back at its spawn point', async () => {
    const sim = await withPlayer();
    hold(sim, 220, quantizeInput(0, 1, -Math.PI / 2, 0, Button.Sprint));
    expect(sim.characters()[0].position.x).toBeGreaterThan(20);
    let lowest = Infinity;
    let respawned = false;
    for (let i = 0; i < 200 && !respawned; i++) {
      hold(sim, 1, IDLE);
      const p = sim.characters()[0].position;
      lowest = Math.min(lowest, p.y);
      respawned = lowest < -10 && Math.abs(p.x) < 0.5 && Math.abs(p.z - 4) < 0.5;
    }
    expect(respawned).toBe(true);
    expect(sim.playerIds()).toEqual([1]);
    sim.destroy();
  });

  it('fills rule defaults and rejects out-of-range rules', () => {
    expect(resolvePlayerRules({})).toEqual({
      walkSpeedMetresPerSecond: 4,
      jumpSpeedMetresPerSecond: 5,
      bulletsHitPlayers: false,
      fireCooldownTicks: 10,
      bulletLifetimeTicks: 120,
      bulletSpeedMetresPerSecond: 40,
      maxPlayers: 64,
      stepUpHeightMetres: 0.4,
      stickToFloorMetres: 0.5,
    });
    expect(() => resolvePlayerRules({ fireCooldownTicks: 0.5 }, 'x')).toThrow(/fireCooldownTicks must be an integer/);
    expect(() => resolvePlayerRules({ walkSpeedMetresPerSecond: NaN }, 'x')).toThrow(/walkSpeedMetresPerSecond/);
  });
});
