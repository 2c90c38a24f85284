// Tests of server/snapshot-fan-out.ts: one snapshot format per room, every frame quantized once and framed once per
// (baseline, descriptors) so members on the same baseline get the very same message, which decodes to the frame;
// events framed once per tick for all members.
import { describe, expect, it } from 'vitest';
import type { RoomSimulation } from '../../server/room-contracts.ts';
import { captureFrame } from '../../server/room-frame.ts';
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

  it('hands out the copies of a superseded frame once, and frames captured into them still decode exactly', () => {
    const { world, fan } = setup();
    const sim = { characters: () => world.characterStates() } as unknown as RoomSimulation;
    const member = new SnapshotEncoder(fan.format);
    const decoder = new SnapshotDecoder(fan.format);
    let reused = 0;
    let previous: WorldFrame | null = null;
    for (let t = 0; t < 12; t++) {
      world.step();
      const spare = fan.takeSpareBodies();
      if (t >= 2) expect(spare, `tick ${t}: the frame before last is free`).not.toBeNull();
      if (spare !== null) {
        expect(spare.ids.buffer).not.toBe(previous?.bodies.ids.buffer); // never the last frame's: the next quantize compares against it
        reused++;
      }
      const r = world.read();
      const expected = quantizeFrame(fan.format, world.tick, { count: r.count, ids: Uint32Array.from(r.ids), states: Float32Array.from(r.states), flags: Uint8Array.from(r.flags) }, world.characterStates());
      const f = captureFrame(world.tick, { count: r.count, ids: r.ids as Uint32Array, states: r.states as Float32Array, flags: r.flags as Uint8Array }, sim, null, spare);
      const sent = fan.snapshotFor(member, f);
      const decoded = decoder.decode(snapshotBytes(sent.message)).frame;
      expect(framesEqual(decoded, expected), `tick ${t}`).toBe(true);
      if (t % 3 === 2) member.acknowledge(world.tick - 1); // an older baseline while later frames reuse its copies
      previous = f;
    }
    expect(reused).toBeGreaterThanOrEqual(10);
  });

  it('describes new bodies once for members that lack all of them, who get the very same message', () => {
    const world = new SyntheticWorld({ seed: 9, bodies: 30, spawnChance: 1, removeChance: 0 });
    const fan = new SnapshotFanOut({ bounds: SYNTH_BOUNDS, isSceneStatic: () => true, describe: (id) => world.describe(id) });
    const frameNow = (): WorldFrame => {
      const r = world.read();
      return { tick: world.tick, bodies: { count: r.count, ids: Uint32Array.from(r.ids), states: Float32Array.from(r.states), flags: Uint8Array.from(r.flags) }, characters: world.characterStates() };
    };
    const first = frameNow();
    const members = ['a', 'b', 'c'].map(() => {
      const encoder = new SnapshotEncoder(fan.format);
      encoder.markDescriptorsKnown(first.bodies.ids);
      const decoder = new SnapshotDecoder(fan.format);
      decoder.decode(snapshotBytes(fan.snapshotFor(encoder, first).message));
      encoder.acknowledge(first.tick);
      return { encoder, decoder };
    });
    world.step();
    world.step(); // two bodies spawned since the members' baseline
    const f = frameNow();
    const spawned = [...f.bodies.ids].filter((id) => !first.bodies.ids.includes(id) && id !== 0x7000_0000);
    expect(spawned).toHaveLength(2);
    members[2].encoder.markDescriptorsKnown([spawned[0]]); // c already holds one of them
    const [a, b, c] = members.map((m) => fan.snapshotFor(m.encoder, f));
    expect(b.message).toBe(a.message);
    expect(b.encoded.descriptors).toBe(a.encoded.descriptors);
    expect(c.message).not.toBe(a.message);
    const expected = quantizeFrame(fan.format, f.tick, f.bodies, f.characters);
    const got = [a, b, c].map((s, i) => {
      const r = decodeServerMessage(s.message);
      if (!r.ok || r.message.type !== 'snapshot') throw new Error('not a snapshot');
      expect(framesEqual(members[i].decoder.decode(r.message.bytes).frame, expected)).toBe(true);
      return r.message.descriptors.map((d) => d.id);
    });
    expect(got).toEqual([spawned, spawned, [spawned[1]]]);
  });

  it('reuses frame buffers while members on slow, stalled and reset streams still decode every snapshot exactly', () => {
    // A buffer handed out again while a member's history still held its frame would turn that member's deltas into
    // deltas against another tick's numbers (a wrong decode), or into full snapshots where deltas were due.
    const world = new SyntheticWorld({ seed: 11, bodies: 60, spawnChance: 0.2, removeChance: 0.1 });
    const fan = new SnapshotFanOut({ bounds: SYNTH_BOUNDS, isSceneStatic: () => true, describe: (id) => world.describe(id) });
    const historySize = 6;
    const ackDelays = [1, 5, 40, 2]; // the third stalls long past its history; the fourth is reset now and then
    const members = ackDelays.map((delay) => ({ delay, encoder: new SnapshotEncoder(fan.format, { historySize }), decoder: new SnapshotDecoder(fan.format), sent: [] as number[], deltas: 0 }));
    for (let t = 0; t < 160; t++) {
      world.step();
      const r = world.read();
      const bodies = { count: r.count, ids: Uint32Array.from(r.ids), states: Float32Array.from(r.states), flags: Uint8Array.from(r.flags) };
      const expected = quantizeFrame(fan.format, world.tick, bodies, world.characterStates());
      const f: WorldFrame = { tick: world.tick, bodies, characters: world.characterStates() };
      for (const [i, m] of members.entries()) {
        if (i === 3 && t % 25 === 24) m.encoder.reset();
        const due = m.sent.filter((tick) => tick <= world.tick - m.delay);
        for (const tick of due) m.encoder.acknowledge(tick);
        m.sent = m.sent.filter((tick) => tick > world.tick - m.delay);
        const sent = fan.snapshotFor(m.encoder, f);
        if (sent.encoded.baselineTick !== null) m.deltas++;
        expect(framesEqual(m.decoder.decode(snapshotBytes(sent.message)).frame, expected), `member ${i}, tick ${world.tick}`).toBe(true);
        m.sent.push(world.tick);
      }
    }
    // Buffers came back and were reused, and members whose acks land inside their history got deltas throughout.
    expect(fan.framePoolCounts.reused).toBeGreaterThan(100);
    expect(members[0].deltas).toBeGreaterThanOrEqual(158);
    expect(members[1].deltas).toBeGreaterThanOrEqual(150);
    expect(members[2].deltas).toBe(0); // acks 40 ticks late: its baselines are long evicted
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
