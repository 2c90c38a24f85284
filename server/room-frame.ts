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

/** `bodies` copied into the spare frame's buffer when it is one of ours and large enough, else into a new one. */
function copyBodies(bodies: BodyStates, spare: BodyStates | null): BodyStates {
  // One buffer for the three arrays: each ArrayBuffer costs the scavenger a sweep entry beside its bytes.
  const count = bodies.count;
  const stateFloats = count * BODY_STATE_STRIDE;
  const bytes = stateFloats * 4 + count * 4 + count;
  const buffer = spare !== null && isOneBuffer(spare) && spare.states.buffer.byteLength >= bytes ? spare.states.buffer : new ArrayBuffer(bytes);
  const states = new Float32Array(buffer, 0, stateFloats);
  const ids = new Uint32Array(buffer, stateFloats * 4, count);
  const flags = new Uint8Array(buffer, stateFloats * 4 + count * 4, count);
  states.set(bodies.states.subarray(0, stateFloats));
  ids.set(bodies.ids.subarray(0, count));
  flags.set(bodies.flags.subarray(0, count));
  return { count, ids, states, flags };
}

/** Whether a frame's arrays are the layout copyBodies makes (states first, then ids and flags, in one buffer). */
function isOneBuffer(b: BodyStates): boolean {
  return b.states.byteOffset === 0 && b.ids.buffer === b.states.buffer && b.flags.buffer === b.states.buffer;
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
