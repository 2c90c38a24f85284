// The floor of every tick: the Jolt work no server can skip, timed over the same ticks a simulation is about to run.
// The honest floor is every present player's character update (CharacterVirtual ExtendedUpdate, driven by the command
// the player last applied) plus the bare PhysicsWorld step; the bare step alone is kept for scenes without players.
// Each batch saves a fast checkpoint, times the ticks, then restores, so the caller runs the very same ticks next.
import { applyCommand, type Player } from '../../shared/sim/players.ts';
import type { SimCore } from '../../shared/sim/sim-core.ts';
import type { Simulation } from '../../shared/sim/simulation.ts';
import { TICK_DT_SECONDS } from '../../shared/tick-rate.ts';

/** One floor tick: the whole of it and its character part (ms). */
export interface FloorTick {
  ms: number;
  characterMs: number;
}

/**
 * The simulation's present players. Simulation keeps its player table private and offers no controller access, so
 * this is the bench's one adapter into its internals; it fails loudly if they change shape.
 */
function presentPlayers(sim: Simulation): { players: readonly Player[]; core: SimCore } {
  const core = (sim as unknown as { core?: SimCore }).core;
  const players = core?.players?.inOrder?.();
  if (!core || !Array.isArray(players)) throw new Error('floorStepBatch: Simulation no longer keeps its player table at sim.core.players; update bench/lib/raw-step.ts');
  return { players, core };
}

/** Times `ticks` bare world.stepFixed() calls from the simulation's current state, then puts it back where it was. */
export function rawStepBatch(sim: Simulation, ticks: number): number[] {
  return floorBatch(sim, ticks, false).map((t) => t.ms);
}

/**
 * Times `ticks` floor ticks (each player's command applied and character moved, in player order as the tick does,
 * then the world step), then puts the simulation back where it was. Fire is left out: spawning a bullet is
 * simulation work, not the engine's floor.
 */
export function floorStepBatch(sim: Simulation, ticks: number): FloorTick[] {
  return floorBatch(sim, ticks, true);
}

function floorBatch(sim: Simulation, ticks: number, characters: boolean): FloorTick[] {
  if (!Number.isInteger(ticks) || ticks < 1) throw new Error(`floor batch: ticks must be a positive integer, got ${ticks}`);
  const { players, core } = characters ? presentPlayers(sim) : { players: [], core: null };
  const cp = sim.saveCheckpoint();
  const out: FloorTick[] = [];
  try {
    const world = sim.world;
    for (let i = 0; i < ticks; i++) {
      const t0 = performance.now();
      let t1 = t0;
      if (core && players.length > 0) {
        for (const p of players) applyCommand(p, p.input, core.rules, sim.tick + i); // walk velocity, jump (aim ignored)
        for (const p of players) p.controller.move(TICK_DT_SECONDS);
        t1 = performance.now();
      }
      world.stepFixed();
      const t2 = performance.now();
      out.push({ ms: t2 - t0, characterMs: t1 - t0 });
    }
    // stepFixed() hands back the floor's sensor transitions (they belong to no tick: dropped here), and the restore
    // puts the sensor overlaps back as they were.
    sim.restoreCheckpoint(cp); // also restores each player's command, fire cooldown and character state
  } finally {
    cp.dispose();
  }
  return out;
}
