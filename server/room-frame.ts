// A room's world frame: the snapshot tick's bodies and characters copied out of the simulation (the simulation's read
// buffers are reused next tick), with the descriptors a held-back frame needs.
import { BODY_STATE_STRIDE } from '../shared/physics/index.ts';
import type { BodyDescriptor } from '../shared/sim/types.ts';
import type { BodyStates, RoomSimulation, WorldFrame } from './room-contracts.ts';

/**
 * Copies `bodies` (this tick's read) and the characters into a frame. `isSceneStatic`: given when the frame may leave
 * after its tick (a durable recording holds it back), to capture the descriptors of its other bodies as of now.
 * `spare`: body arrays no one reads any more (SnapshotFanOut.takeSpareBodies) to copy into instead of allocating:
 * after a Jolt step a fresh 1000-body allocation costs tens of µs (sometimes 0.1–0.2 ms), a copy into spare arrays ~5 µs.
 */
export function captureFrame(tick: number, bodies: BodyStates, sim: RoomSimulation, isSceneStatic: ((id: number) => boolean) | null, spare: BodyStates | null = null): WorldFrame {
  const frame: WorldFrame = { tick, bodies: copyBodies(bodies, spare), characters: sim.characters() };
  if (isSceneStatic) frame.descriptors = captureDescriptors(frame.bodies, sim, isSceneStatic);
  return frame;
}

/** `bodies` copied into the spare arrays when they are large enough (views of their first `count` entries), else new ones. */
function copyBodies(bodies: BodyStates, spare: BodyStates | null): BodyStates {
  const n = bodies.count;
  const ids = spare !== null && spare.ids.buffer.byteLength >= n * 4 ? new Uint32Array(spare.ids.buffer, 0, n) : new Uint32Array(n);
  const states = spare !== null && spare.states.buffer.byteLength >= n * BODY_STATE_STRIDE * 4 ? new Float32Array(spare.states.buffer, 0, n * BODY_STATE_STRIDE) : new Float32Array(n * BODY_STATE_STRIDE);
  const flags = spare !== null && spare.flags.buffer.byteLength >= n ? new Uint8Array(spare.flags.buffer, 0, n) : new Uint8Array(n);
  ids.set(bodies.ids.subarray(0, n));
  states.set(bodies.states.subarray(0, n * BODY_STATE_STRIDE));
  flags.set(bodies.flags.subarray(0, n));
  return { count: n, ids, states, flags };
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
