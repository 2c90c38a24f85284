// Tests of server/snapshot-fan-out.ts: one snapshot format per room, every frame quantized once and framed once per
// (baseline, descriptors) so members on the same baseline get the very same message, which decodes to the frame;
// events framed once per tick for all members.
import { describe, expect, it } from 'vitest';
import type { WorldFrame } from '../../server/room.ts';
import { SnapshotFanOut } from '../../server/snapshot-fan-out.ts';
import { decodeServerMessage, framesEqual, quantizeFrame, SnapshotDecoder, SnapshotEncoder } from '../../shared/protocol/index.ts';
import type { SimEvent } from '../../shared/sim/types.ts';
import { SYNTH_BOUNDS, SyntheticWorld } from '../shared/protocol/synthetic-world.ts';

function setup() {
  const world = new SyntheticWorld({ seed: 7, bodies: 40 });
  const fan = new SnapshotFanOut({ bounds: SYNTH_BOUNDS, isSceneStatic: () => true, describe: (id) => world.describe(id) });
  const frame = (): WorldFrame => {
    const r = world.read();
    const bodies = { count: r.count, ids: Uint32Array.from(r.ids), states: Float32Array.from(r.states), flags: Uint8Array.from(r.flags) };
    return { tick: world.tick, bodies, characters: world.characterStates() };
  };
  return { world, fan, frame };
}

/** The snapshot bytes inside a framed server message. */
function snapshotBytes(message: Uint8Array): Uint8Array {
  const r = decodeServerMessage(message);
  if (!r.ok || r.message.type !== 'snapshot') throw new Error(`not a snapshot message: ${JSON.stringify(r)}`);
  return r.message.bytes;
}

describe('SnapshotFanOut', () => {
  it('gives members on the same baseline the very same message, which decodes to the quantized frame', () => {
    const { world, fan, frame } = setup();
    world.step();
    const f = frame();
    const a = fan.snapshotFor(new SnapshotEncoder(fan.format), f);
    const b = fan.snapshotFor(new SnapshotEncoder(fan.format), f);
    expect(b.message).toBe(a.message);
    expect(a.encoded.baselineTick).toBeNull();
    const decoded = new SnapshotDecoder(fan.format).decode(snapshotBytes(a.message)).frame;
    expect(framesEqual(decoded, quantizeFrame(fan.format, f.tick, f.bodies, f.characters))).toBe(true);
    expect(fan.format).toBe(fan.format);
  });

  it('frames a member on another baseline its own message, and a new frame anew', () => {
    const { world, fan, frame } = setup();
    const acking = new SnapshotEncoder(fan.format);
    const fresh = new SnapshotEncoder(fan.format);
    world.step();
    const first = frame();
    fan.snapshotFor(acking, first);
    acking.acknowledge(first.tick);
    world.step();
    const second = frame();
    const delta = fan.snapshotFor(acking, second);
    const full = fan.snapshotFor(fresh, second);
    const fullAgain = fan.snapshotFor(new SnapshotEncoder(fan.format), second);
    expect(delta.encoded.baselineTick).toBe(first.tick);
    expect(full.encoded.baselineTick).toBeNull();
    expect(delta.message).not.toBe(full.message);
    expect(fullAgain.message).toBe(full.message);
    const decoder = new SnapshotDecoder(fan.format);
    decoder.decode(snapshotBytes(fan.snapshotFor(new SnapshotEncoder(fan.format), first).message));
    const viaDelta = decoder.decode(snapshotBytes(delta.message)).frame;
    expect(framesEqual(viaDelta, quantizeFrame(fan.format, second.tick, second.bodies, second.characters))).toBe(true);
  });

  it('frames the events of a tick once for every member', () => {
    const { fan } = setup();
    const events: SimEvent[] = [{ type: 'playerJoined', tick: 3, playerId: 1, name: 'ann' }];
    const message = fan.eventsMessage(events);
    expect(fan.eventsMessage(events)).toBe(message);
    expect(decodeServerMessage(message)).toEqual({ ok: true, message: { type: 'events', events } });
    const next: SimEvent[] = [{ type: 'playerLeft', tick: 4, playerId: 1 }];
    expect(fan.eventsMessage(next)).not.toBe(message);
  });
});
