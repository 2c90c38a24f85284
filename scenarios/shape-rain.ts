// shape-rain: boxes, spheres, capsules and convex hulls rain onto a walled ground, a few per tick, until `count`
// bodies exist; optionally each body is re-dropped after a lifetime, for an endless rain. The benchmark scene.
import type { ScenarioContext, ScenarioDefinition, ScenarioInstance } from '../shared/sim/scenario.ts';
import { PROP_COLORS } from './lib/palette.ts';
import { randomMixedShape, randomUnitQuat } from './lib/random-shapes.ts';
import { addBoundaryWalls, addGround } from './lib/static-scene.ts';

const WALKWAY_METRES = 3;
/** Angular damping of round shapes stands in for rolling resistance, so a sphere on the flat comes to rest. */
const ROLLING_DAMPING: Readonly<Record<string, number>> = { sphere: 1.2, capsule: 1.2 };

/**
 * `live` without the pairs whose body the world no longer holds (the same array when none is gone). Drop order is
 * creation order, so its ids ascend like the world's: one merge walk over both dense id lists instead of a handle
 * lookup per live body, which after a step misses the cache for nearly every body. Falls back to lookups should the
 * ids not ascend.
 */
function keepPresent(live: number[], c: ScenarioContext): number[] {
  const present = c.world.bodyIds();
  let kept: number[] | null = null;
  let j = 0;
  let prev = -1;
  for (let i = 0; i < live.length; i += 2) {
    const id = live[i];
    if (id <= prev) return keepPresentByLookup(live, c);
    prev = id;
    while (j < present.length && present[j] < id) j++;
    if (j < present.length && present[j] === id) {
      if (kept !== null) kept.push(id, live[i + 1]);
    } else if (kept === null) {
      kept = live.slice(0, i);
    }
  }
  return kept ?? live;
}

function keepPresentByLookup(live: number[], c: ScenarioContext): number[] {
  const kept: number[] = [];
  for (let i = 0; i < live.length; i += 2) if (c.world.getBody(live[i])) kept.push(live[i], live[i + 1]);
  return kept;
}

/** Boxes, spheres, capsules and hulls raining on a walled ground. */
export const scenario: ScenarioDefinition = {
  name: 'shape-rain',
  description: 'Boxes, spheres, capsules and convex hulls rain onto a walled ground and pile up.',
  params: {
    count: { default: 300, min: 1, max: 4000, integer: true, description: 'bodies rained in total (alive at once)' },
    spawnPerTick: { default: 4, min: 1, max: 200, integer: true, description: 'bodies dropped per tick until count is reached' },
    areaMetres: { default: 16, min: 4, max: 60, description: 'side of the square the shapes fall onto (m)' },
    dropHeightMetres: { default: 12, min: 2, max: 40, description: 'height shapes are dropped from (m)' },
    sizeMetres: { default: 0.35, min: 0.1, max: 1, description: 'typical half-size of a shape (m)' },
    recycleAfterTicks: { default: 0, min: 0, max: 36000, integer: true, description: 're-drop a body this many ticks after it fell (0: never, the pile settles)' },
  },
  bounds: { min: { x: -40, y: -10, z: -40 }, max: { x: 40, y: 60, z: 40 } },
  golden: { ticks: 240, bots: 1 },
  // Measured at 300 bodies: 128 players take ~3.7 ms of simulation per tick on one core (bench/character-cost.ts);
  // past ~176 the 16 spawn slots crowd and character updates explode (issue 14).
  players: { maxPlayers: 128 },
  world: { maxBodies: 10240, maxBodyPairs: 65536, maxContactConstraints: 16384 },
  build(ctx: ScenarioContext): ScenarioInstance {
    const p = ctx.params;
    const half = p.areaMetres / 2;
    const inner = half + WALKWAY_METRES;
    addGround(ctx, inner + 1);
    addBoundaryWalls(ctx, inner, 1.5);
    // Live bodies in drop order: [bodyId, tick dropped] pairs. Ids, not handles, survive checkpoints.
    let live: number[] = [];
    let dropped = 0;

    const drop = (c: ScenarioContext): void => {
      const shape = randomMixedShape(c.rng, p.sizeMetres);
      const pos = { x: c.rng.range(-half, half), y: p.dropHeightMetres + c.rng.range(0, 2), z: c.rng.range(-half, half) };
      const body = c.spawn(shape, pos, randomUnitQuat(c.rng), { motion: 'dynamic', friction: 0.5, restitution: 0.2, angularDamping: ROLLING_DAMPING[shape.kind] ?? 0.3, color: c.rng.pick(PROP_COLORS), name: `rain ${dropped}` });
      live.push(body.id, c.tick);
      dropped++;
    };

    return {
      spawnPoint(playerIndex: number) {
        const slot = playerIndex % 16;
        return { x: -half + 0.5 + (slot % 8) * ((2 * half - 1) / 7), y: 0.05, z: half + WALKWAY_METRES / 2 + (slot >= 8 ? -1 : 0) };
      },
      onTick(c: ScenarioContext) {
        // Forget bodies the simulation removed (left the bounds); keep the drop order of the rest.
        live = keepPresent(live, c);
        let budget = p.spawnPerTick;
        if (p.recycleAfterTicks > 0) {
          while (budget > 0 && live.length > 0 && c.tick - live[1] >= p.recycleAfterTicks) {
            c.remove(live[0]);
            live.splice(0, 2);
            drop(c);
            budget--;
          }
        }
        while (budget > 0 && live.length / 2 < p.count) {
          drop(c);
          budget--;
        }
      },
      saveState() {
        return [dropped, ...live];
      },
      restoreState(state: readonly number[]) {
        if (state.length < 1 || (state.length - 1) % 2 !== 0) throw new Error(`shape-rain: bad saved state (length ${state.length})`);
        dropped = state[0];
        live = state.slice(1);
      },
    };
  },
};
