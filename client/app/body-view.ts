// Turns a simulation's bulk body read (ids ascending, BODY_STATE_STRIDE floats and BodyFlag bits per body) and its
// characters into the SnapshotView the world view draws: what the page shows when it runs the simulation itself
// (replay viewer, predicted play) instead of interpolating snapshots. Static bodies are left out (drawn once).
import { BODY_STATE_STRIDE, BodyFlag } from '../../shared/physics-data/body-state.ts';
import type { BodyStatesRead, SnapshotView } from '../../shared/protocol/snapshot-frame.ts';
import type { CharacterState } from '../../shared/sim/types.ts';

/** The moving bodies of `read` and `characters` as a SnapshotView of `tick` (copies). */
export function viewFromBodyStates(tick: number, read: BodyStatesRead, characters: CharacterState[]): SnapshotView {
  let moving = 0;
  for (let i = 0; i < read.count; i++) if ((read.flags[i] & BodyFlag.Static) === 0) moving++;
  const ids = new Uint32Array(moving);
  const positions = new Float32Array(moving * 3);
  const rotations = new Float32Array(moving * 4);
  const atRest = new Uint8Array(moving);
  let k = 0;
  for (let i = 0; i < read.count; i++) {
    const flags = read.flags[i];
    if ((flags & BodyFlag.Static) !== 0) continue;
    const s = i * BODY_STATE_STRIDE;
    ids[k] = read.ids[i];
    positions[k * 3] = read.states[s];
    positions[k * 3 + 1] = read.states[s + 1];
    positions[k * 3 + 2] = read.states[s + 2];
    rotations[k * 4] = read.states[s + 3];
    rotations[k * 4 + 1] = read.states[s + 4];
    rotations[k * 4 + 2] = read.states[s + 5];
    rotations[k * 4 + 3] = read.states[s + 6];
    atRest[k] = (flags & BodyFlag.Active) === 0 ? 1 : 0;
    k++;
  }
  return { tick, ids, positions, rotations, atRest, characters };
}
