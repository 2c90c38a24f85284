// crowd-arena: a flat walled arena made for crowds. Every player slot up to the scenario's player cap has its own
// spawn point on a square grid (no two joins share one until the cap is reached), and a few hundred props rest between
// the spawn points for players to push around. The clients-per-core crowd scene (issue 14 item 2).
import type { ScenarioContext, ScenarioDefinition, ScenarioInstance } from '../shared/sim/scenario.ts';
import type { Vec3Like } from '../shared/physics/index.ts';
import { PROP_COLORS } from './lib/palette.ts';
import { randomMixedShape, randomUnitQuat } from './lib/random-shapes.ts';
import { addBoundaryWalls, addGround } from './lib/static-scene.ts';

/** Most players in one room: every one has its own spawn point. */
export const CROWD_ARENA_MAX_PLAYERS = 512;
/** Distance between two neighbouring spawn points (m): a capsule is 0.7 m wide, a prop at most ~0.8 m. */
export const SPAWN_SPACING_METRES = 2.4;
/** Free strip between the outermost spawn points and the walls (m). */
const MARGIN_METRES = 2;
const PROP_SIZE_METRES = 0.3;

/** Spawn points per side of the square grid that holds every slot. */
export function spawnGridSide(slots: number): number {
  let side = 1;
  while (side * side < slots) side++;
  return side;
}

/** Feet position of spawn slot `slot` on a `side`×`side` grid centred on the origin. */
export function spawnSlotPosition(slot: number, side: number): Vec3Like {
  const offset = ((side - 1) * SPAWN_SPACING_METRES) / 2;
  return { x: (slot % side) * SPAWN_SPACING_METRES - offset, y: 0.05, z: Math.floor(slot / side) * SPAWN_SPACING_METRES - offset };
}

/** Half the side of the walled floor for a grid of `side` spawn points per row (m). */
export function arenaHalfMetres(side: number): number {
  return ((side - 1) * SPAWN_SPACING_METRES) / 2 + MARGIN_METRES;
}

const SIDE = spawnGridSide(CROWD_ARENA_MAX_PLAYERS);
const HALF = arenaHalfMetres(SIDE);

/** A walled floor sized to the player cap, one spawn point per player slot, props resting between them. */
export const scenario: ScenarioDefinition = {
  name: 'crowd-arena',
  description: `A flat walled arena for crowds: up to ${CROWD_ARENA_MAX_PLAYERS} players, each with its own spawn point, among resting props.`,
  params: {
    props: { default: 256, min: 0, max: (SIDE - 1) * (SIDE - 1), integer: true, description: 'props resting between the spawn points' },
  },
  bounds: { min: { x: -HALF - 10, y: -10, z: -HALF - 10 }, max: { x: HALF + 10, y: 40, z: HALF + 10 } },
  golden: { ticks: 240, bots: 8 },
  // A flat floor: no stairs to walk up, so no stair sweeps each time a player bumps into another.
  players: { maxPlayers: CROWD_ARENA_MAX_PLAYERS, stepUpHeightMetres: 0 },
  world: { maxBodies: 4096, maxBodyPairs: 65536, maxContactConstraints: 16384 },
  build(ctx: ScenarioContext): ScenarioInstance {
    addGround(ctx, HALF + 1);
    addBoundaryWalls(ctx, HALF, 3); // taller than a jump plus a stair step
    // Props sit at the centres of the grid's cells (1.7 m from each corner's spawn point), cells drawn without repeats.
    const cells = Array.from({ length: (SIDE - 1) * (SIDE - 1) }, (_, i) => i);
    for (let n = 0; n < ctx.params.props; n++) {
      const pick = n + ctx.rng.int(0, cells.length - n - 1);
      const cell = cells[pick];
      cells[pick] = cells[n];
      cells[n] = cell;
      const corner = spawnSlotPosition((cell % (SIDE - 1)) + Math.floor(cell / (SIDE - 1)) * SIDE, SIDE);
      const shape = randomMixedShape(ctx.rng, PROP_SIZE_METRES);
      const at = { x: corner.x + SPAWN_SPACING_METRES / 2, y: 2 * PROP_SIZE_METRES + 0.1, z: corner.z + SPAWN_SPACING_METRES / 2 };
      ctx.spawn(shape, at, randomUnitQuat(ctx.rng), { motion: 'dynamic', friction: 0.6, restitution: 0.1, angularDamping: 0.8, color: ctx.rng.pick(PROP_COLORS), name: `prop ${n}` });
    }
    return {
      spawnPoint(playerIndex: number) {
        return spawnSlotPosition(playerIndex % CROWD_ARENA_MAX_PLAYERS, SIDE);
      },
    };
  },
};
