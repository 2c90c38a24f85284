// Loads the physics chunk (client/physics/: the browser's own Simulation with Jolt) on first use and starts Jolt;
// later calls share the same load. The only door from a page to the engine: a dynamic import().
import type * as PhysicsChunk from '../physics/index.ts';

/** What the physics chunk exports. */
export type Physics = typeof PhysicsChunk;

let loading: Promise<Physics> | null = null;

/** The physics chunk with Jolt loaded; fetched once per page (a failed load may be retried). */
export function loadPhysics(): Promise<Physics> {
  if (!loading) {
    loading = import('../physics/index.ts').then(async (chunk) => {
      await chunk.startPhysics();
      return chunk;
    });
    loading.catch(() => {
      loading = null;
    });
  }
  return loading;
}
