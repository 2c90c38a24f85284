// Tests of bullets: muzzle geometry clear of the shooter's capsule, hitting the world, never hitting the shooter,
// hitting other players only when the scenario says so, fire cooldown and lifetime.
import { describe, expect, it } from 'vitest';
import { BULLET_RADIUS_METRES, capsuleExitDistance, muzzlePosition } from '../../../shared/sim/bullets.ts';
import { Button, quantizeInput } from '../../../shared/sim/input.ts';
import { CHARACTER_HALF_HEIGHT_METRES as H, CHARACTER_RADIUS_METRES as R } from '../../../shared/sim/players.ts';
import type { ScenarioDefinition } from '../../../shared/sim/scenario.ts';
import { Simulation } from '../../../shared/sim/simulation.ts';
import type { SimEvent } from '../../../shared/sim/types.ts';
import { IDLE, makeSim, record } from './helpers/sim-helpers.ts';
import { testArena, testArenaPvp, WALL_FACE_Z } from './helpers/test-scenarios.ts';

/** Distance from p to the shooter's capsule axis segment (feet at the origin). */
function axisDistance(p: { x: number; y: number; z: number }): number {
  const cy = Math.min(R + 2 * H, Math.max(R, p.y));
  return Math.hypot(p.x, p.y - cy, p.z);
}

const FIRE = (yawRadians: number, pitchRadians = 0) => quantizeInput(0, 0, yawRadians, pitchRadians, Button.Fire);

/** Steps `ticks` ticks (player commands from `command(t)`), returning events and the y-z-x track of `track()`. */
function run(sim: Simulation, ticks: number, command: (t: number) => Record<number, ReturnType<typeof FIRE>>): SimEvent[] {
  const events: SimEvent[] = [];
  for (let i = 0; i < ticks; i++) {
    const cmds = command(sim.tick);
    const commands = Object.keys(cmds).map((id) => ({ playerId: Number(id), input: cmds[Number(id)] }));
    events.push(...sim.step(record(sim.tick, { commands })));
  }
  return events;
}

function spawnedIds(events: SimEvent[]): number[] {
  return events.filter((e) => e.type === 'bodySpawned').map((e) => (e as { bodyId: number }).bodyId);
}

async function arenaWith(def: ScenarioDefinition, players: number[]): Promise<Simulation> {
  const sim = await makeSim(def, { spawnEvery: 0, boxes: 0 });
  sim.step(record(0, { joins: players.map((playerId) => ({ playerId, name: `p${playerId}` })) }));
  return sim;
}

describe('bullets', () => {
  it('computes where any aim leaves the shooter capsule', () => {
    for (let i = 0; i <= 64; i++) {
      const pitch = -Math.PI / 2 + (Math.PI * i) / 64;
      const aim = { x: Math.cos(pitch) * Math.sin(i), y: Math.sin(pitch), z: Math.cos(pitch) * Math.cos(i) };
      const t = capsuleExitDistance(aim);
      expect(axisDistance({ x: aim.x * t, y: 1.7 + aim.y * t, z: aim.z * t })).toBeCloseTo(R, 9);
    }
  });

  it('starts every bullet outside the shooter capsule, even aiming straight down or up', () => {
    for (const aim of [{ x: 0, y: -1, z: 0 }, { x: 0, y: 1, z: 0 }, { x: 1, y: 0, z: 0 }, { x: 0.6, y: -0.8, z: 0 }]) {
      expect(axisDistance(muzzlePosition({ x: 0, y: 0, z: 0 }, aim))).toBeGreaterThan(R + BULLET_RADIUS_METRES);
    }
  });

  it('hits the world: a shot at the wall bounces off its face instead of passing through', async () => {
    const sim = await arenaWith(testArena, [1]);
    const events = run(sim, 1, () => ({ 1: FIRE(0) }));
    const [bullet] = spawnedIds(events);
    let minZ = Infinity;
    for (let i = 0; i < 30; i++) {
      run(sim, 1, () => ({}));
      minZ = Math.min(minZ, sim.world.getBody(bullet)!.position().z);
    }
    expect(minZ).toBeLessThan(WALL_FACE_Z + 0.5);
    expect(minZ).toBeGreaterThan(WALL_FACE_Z);
    expect(sim.world.getBody(bullet)!.linearVelocity().z).toBeGreaterThan(0);
    sim.destroy();
  });

  it('passes through its own shooter when bullets hit players', async () => {
    const sim = await arenaWith(testArenaPvp, [1]);
    run(sim, 95, () => ({ 1: quantizeInput(0, 1, 0, 0, Button.Sprint) }));
    run(sim, 10, () => ({ 1: { ...IDLE } }));
    const shooterZ = sim.characters()[0].position.z;
    expect(shooterZ).toBeLessThan(WALL_FACE_Z + 2);
    const [bullet] = spawnedIds(run(sim, 1, () => ({ 1: FIRE(0) })));
    let maxZ = -Infinity;
    for (let i = 0; i < 30; i++) {
      run(sim, 1, () => ({ 1: { ...IDLE } }));
      maxZ = Math.max(maxZ, sim.world.getBody(bullet)!.position().z);
    }
    expect(maxZ).toBeGreaterThan(shooterZ + R + 0.3);
    sim.destroy();
  });

  it('hits another player when the scenario says bullets hit players, and passes through otherwise', async () => {
    const farX: Record<string, number> = {};
    for (const def of [testArenaPvp, testArena]) {
      const sim = await arenaWith(def, [1, 2]);
      run(sim, 10, () => ({}));
      const [bullet] = spawnedIds(run(sim, 1, () => ({ 1: FIRE(-Math.PI / 2) })));
      let maxX = -Infinity;
      for (let i = 0; i < 20; i++) {
        run(sim, 1, () => ({}));
        maxX = Math.max(maxX, sim.world.getBody(bullet)!.position().x);
      }
      farX[def.name] = maxX;
      sim.destroy();
    }
    expect(farX['test-arena-pvp']).toBeLessThan(1.5);
    expect(farX['test-arena']).toBeGreaterThan(5);
  });

  it('fires at most once per cooldown while Fire is held, and removes each bullet after its lifetime', async () => {
    const sim = await arenaWith(testArena, [1]);
    const events = run(sim, 60, (t) => (t < 20 ? { 1: FIRE(Math.PI, 0.3) } : { 1: { ...IDLE } }));
    const spawns = events.filter((e) => e.type === 'bodySpawned');
    expect(spawns.map((e) => e.tick)).toEqual([1, 7, 13, 19]);
    const removals = events.filter((e) => e.type === 'bodyRemoved');
    expect(removals.map((e) => e.tick)).toEqual([40, 46, 52, 58]);
    expect(removals.map((e) => (e as { bodyId: number }).bodyId)).toEqual(spawns.map((e) => (e as { bodyId: number }).bodyId));
    sim.destroy();
  });

  it('drops a shot instead of failing when the world is full', async () => {
    const sim = await Simulation.create({ scenario: testArena, params: { spawnEvery: 0, boxes: 0 }, worldOptions: { maxBodies: 4 } });
    sim.step(record(0, { joins: [{ playerId: 1, name: 'p' }] }));
    const events = run(sim, 12, () => ({ 1: FIRE(0) }));
    expect(spawnedIds(events)).toEqual([]);
    expect(sim.tick).toBe(13);
    sim.destroy();
  });
});
