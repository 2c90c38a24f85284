// Small deterministic scenarios for the simulation tests: a walled arena with a box stack, a trigger zone, a wall to
// shoot at, a kinematic platform and a seeded spawner; plus a variant that builds the same scene in reverse order.
import type { ScenarioContext, ScenarioDefinition, ScenarioInstance } from '../../../../shared/sim/scenario.ts';

/** Where the trigger zone sits (a 2 × 2 × 2 m box centred here, clear of the ground). */
export const ZONE_CENTRE = { x: 6, y: 1.2, z: 0 };
/** The shooting wall: a static box whose near face is at z = WALL_FACE_Z (players stand at larger z). */
export const WALL_FACE_Z = -8;

function buildArena(ctx: ScenarioContext, reverse: boolean): ScenarioInstance {
  const p = ctx.params;
  const steps: Array<() => void> = [];
  steps.push(() => ctx.spawn({ kind: 'box', halfExtents: { x: 20, y: 0.5, z: 20 } }, { x: 0, y: -0.5, z: 0 }, null, { motion: 'static', name: 'ground' }));
  steps.push(() => ctx.spawn({ kind: 'box', halfExtents: { x: 20, y: 3, z: 0.5 } }, { x: 0, y: 3, z: WALL_FACE_Z - 0.5 }, null, { motion: 'static', name: 'wall' }));
  for (let i = 0; i < p.boxes; i++) {
    const x = -4 + (i % 4) * 0.7;
    const y = 0.3 + Math.floor(i / 4) * 0.62;
    steps.push(() => ctx.spawn({ kind: 'box', halfExtents: { x: 0.3, y: 0.3, z: 0.3 } }, { x, y, z: 2 }, null, { motion: 'dynamic', friction: 0.6, name: `crate ${i}` }));
  }
  steps.push(() =>
    ctx.spawn({ kind: 'box', halfExtents: { x: 1, y: 1, z: 1 } }, ZONE_CENTRE, null, { motion: 'kinematic', isSensor: true, hidden: true, name: 'zone' }),
  );
  if (reverse) steps.reverse();
  for (const s of steps) s();
  let spawned: number[] = [];
  let zoneVisits = 0;
  return {
    spawnPoint(n: number) {
      return { x: (n % 4) * 1.5, y: 0, z: 4 + Math.floor(n / 4) * 1.5 };
    },
    onTick(c: ScenarioContext) {
      if (p.spawnEvery > 0 && c.tick % p.spawnEvery === 0) {
        const b = c.spawn({ kind: 'sphere', radius: 0.25 }, { x: c.rng.range(-3, 3), y: 5, z: c.rng.range(-1, 1) }, null, { motion: 'dynamic', restitution: 0.4, color: [0.2, 0.6, 0.9] });
        spawned.push(b.id);
        if (spawned.length > 4) c.remove(spawned.shift()!);
      }
    },
    onEvents(c: ScenarioContext, events) {
      for (const e of events) {
        if (e.type === 'sensorEnter' && e.playerId !== undefined) {
          zoneVisits++;
          c.emit('zoneVisit', e.playerId);
        }
      }
    },
    saveState() {
      return [zoneVisits, ...spawned];
    },
    restoreState(state: readonly number[]) {
      zoneVisits = state[0];
      spawned = state.slice(1);
    },
  };
}

function arena(name: string, reverse: boolean, bulletsHitPlayers: boolean): ScenarioDefinition {
  return {
    name,
    description: 'test arena: crates, a trigger zone, a wall, a seeded sphere spawner',
    params: {
      boxes: { default: 8, min: 0, max: 400, integer: true, description: 'crates in the stack' },
      spawnEvery: { default: 15, min: 0, max: 600, integer: true, description: 'ticks between sphere spawns (0: none)' },
    },
    bounds: { min: { x: -30, y: -20, z: -30 }, max: { x: 30, y: 40, z: 30 } },
    golden: { ticks: 120, bots: 2 },
    players: { bulletLifetimeTicks: 40, fireCooldownTicks: 6, bulletsHitPlayers },
    world: { maxBodies: 2048 },
    build: (ctx) => buildArena(ctx, reverse),
  };
}

/** The arena. */
export const testArena = arena('test-arena', false, false);
/** The same scene with every body created in reverse order. */
export const testArenaReversed = arena('test-arena', true, false);
/** The arena where bullets hit players (never their shooter). */
export const testArenaPvp = arena('test-arena-pvp', false, true);
