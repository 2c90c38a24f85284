// A room's world frame: the snapshot tick's bodies and characters copied out of the simulation (the simulation's read
// buffers are reused next tick), with the descriptors a held-back frame needs.
import { BODY_STATE_STRIDE } from '../shared/physics/index.ts';
import type { BodyDescriptor } from '../shared/sim/types.ts';
import type { BodyStates, RoomSimulation, WorldFrame } from './room-contracts.ts';

/**
 * Copies `bodies` (this tick's read) and the characters into a frame. `isSceneStatic`: given when the frame may leave
 * after its tick (a durable recording holds it back), to capture the descriptors of its other bodies as of now.
 */
export function captureFrame(tick: number, bodies: BodyStates, sim: RoomSimulation, isSceneStatic: ((id: number) => boolean) | null): WorldFrame {
  const frame: WorldFrame = {
    tick,
    bodies: {
      count: bodies.count,
      ids: copyOf(bodies.ids, bodies.count, (n) => new Uint32Array(n)),
      states: copyOf(bodies.states, bodies.count * BODY_STATE_STRIDE, (n) => new Float32Array(n)),
      flags: copyOf(bodies.flags, bodies.count, (n) => new Uint8Array(n)),
    },
    characters: sim.characters(),
  };
  if (isSceneStatic) frame.descriptors = captureDescriptors(frame.bodies, sim, isSceneStatic);
  return frame;
}

/**
 * The first `n` values of `from` in a new array. Not `from.slice(0, n)`: on a subarray (the read buffers are views) V8
 * copies a Float32Array's slice one element at a time, ~25× slower than allocating and set() (~130 µs for 1000 bodies).
 */
function copyOf<T extends Uint32Array | Float32Array | Uint8Array>(from: T, n: number, make: (n: number) => T): T {
  const out = make(n);
  out.set(from.subarray(0, n));
  return out;
}

function captureDescriptors(bodies: BodyStates, sim: RoomSimulation, isSceneStatic: (id: number) => boolean): Map<number, BodyDescriptor> {
  const out = new Map<number, BodyDescriptor>();
  for (let i = 0; i < bodies.count; i++) {
    const id = bodies.ids[i];
    if (isSceneStatic(id)) continue;
    const d = sim.bodyDescriptor(id);
    if (d) out.set(id, d);
  }
  return out;
}
