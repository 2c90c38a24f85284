// The floor of every tick: the raw PhysicsWorld step loop over the same ticks a simulation is about to run. It saves
// a fast checkpoint, times `ticks` bare world.stepFixed() calls, then restores, so the caller goes on to run the
// very same ticks through the full path (interleaved batches: machine noise hits both sides alike).
import type { Simulation } from '../../shared/sim/simulation.ts';

/** Times `ticks` raw Jolt steps from the simulation's current state, then puts the simulation back where it was. */
export function rawStepBatch(sim: Simulation, ticks: number): number[] {
  if (!Number.isInteger(ticks) || ticks < 1) throw new Error(`rawStepBatch: ticks must be a positive integer, got ${ticks}`);
  const cp = sim.saveCheckpoint();
  const times: number[] = [];
  try {
    const world = sim.world;
    for (let i = 0; i < ticks; i++) {
      const t0 = performance.now();
      world.stepFixed();
      times.push(performance.now() - t0);
    }
    // stepFixed() hands back the raw steps' sensor transitions (they belong to no tick: dropped here), and the
    // restore puts the sensor overlaps back as they were.
    sim.restoreCheckpoint(cp);
  } finally {
    cp.dispose();
  }
  return times;
}
