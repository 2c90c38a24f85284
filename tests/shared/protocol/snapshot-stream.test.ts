// Tests of the per-client snapshot streams: acks pick the baseline, lost and reordered acks and snapshots never
// break decoding, hostile raw snapshot frames mid-stream fail clearly, evicted baselines fall back to full snapshots, descriptors are resent until acked, and a real
// Jolt stream decodes to the server's exact frames.
import { describe, expect, it } from 'vitest';
import { createSnapshotFormat } from '../../../shared/protocol/quantization.ts';
import { encodeServerMessage } from '../../../shared/protocol/codec.ts';
import { decodeServerMessage } from '../../../shared/protocol/server-message-decoder.ts';
import { decodeSnapshot } from '../../../shared/protocol/snapshot-codec.ts';
import { framesEqual, quantizeFrame, type QuantizedFrame } from '../../../shared/protocol/snapshot-frame.ts';
import { SharedFrameWork, SnapshotDecoder, SnapshotEncoder, TickHistory, type EncodedSnapshot } from '../../../shared/protocol/snapshot-stream.ts';
import { Prng } from '../../../shared/sim/prng.ts';
import { scenario as cubes901 } from '../../../scenarios/cubes-901.ts';
import { BotScript } from '../../../shared/sim/bots.ts';
import { Simulation } from '../../../shared/sim/simulation.ts';
import { makeWorld } from '../../helpers/physics.ts';
import { SYNTH_BOUNDS, SyntheticWorld } from './synthetic-world.ts';

const format = createSnapshotFormat(SYNTH_BOUNDS);

function frameOf(world: SyntheticWorld): QuantizedFrame {
  return quantizeFrame(format, world.tick, world.read(), world.characterStates());
}

describe('snapshot-stream', () => {
  it('keeps the newest ticks of a history, in order or after late entries', () => {
    const inOrder = new TickHistory<number>(3);
    for (let t = 10; t < 20; t++) inOrder.set(t, t);
    expect([17, 18, 19].map((t) => inOrder.get(t))).toEqual([17, 18, 19]);
    expect(inOrder.get(16)).toBeUndefined();
    const late = new TickHistory<number>(3);
    for (const t of [10, 11, 12, 5, 13, 14, 3, 15]) late.set(t, t);
    // A late, stale tick is the first to go: the three newest stay.
    expect([13, 14, 15].map((t) => late.get(t))).toEqual([13, 14, 15]);
    expect(late.size).toBe(3);
    late.clear();
    for (let t = 1; t <= 5; t++) late.set(t, t);
    expect([3, 4, 5].map((t) => late.get(t))).toEqual([3, 4, 5]);
  });

  it('sends full snapshots until an ack arrives, then deltas against the newest acked tick', () => {
    const world = new SyntheticWorld({ seed: 1 });
    const enc = new SnapshotEncoder(format);
    const dec = new SnapshotDecoder(format);
    const describe = (id: number) => world.describe(id);
    world.step();
    const s1 = enc.encode(frameOf(world), describe);
    world.step();
    const s2 = enc.encode(frameOf(world), describe);
    expect([s1.baselineTick, s2.baselineTick]).toEqual([null, null]);
    dec.decode(s1.bytes);
    expect(enc.acknowledge(1)).toBe('baseline');
    world.step();
    const s3 = enc.encode(frameOf(world), describe);
    expect(s3.baselineTick).toBe(1);
    expect(s3.bytes.length).toBeLessThan(s1.bytes.length / 3);
    expect(framesEqual(dec.decode(s3.bytes).frame, frameOf(world))).toBe(true);
    expect(enc.stats).toMatchObject({ full: 2, delta: 1, acks: 1 });
  });

  it('shares one encoding between clients that acked the same tick, and keeps each decode exact', () => {
    const world = new SyntheticWorld({ seed: 3 });
    const describe = (id: number) => world.describe(id);
    const encoders = [new SnapshotEncoder(format), new SnapshotEncoder(format), new SnapshotEncoder(format)];
    const decoders = encoders.map(() => new SnapshotDecoder(format));
    const sendAll = (): EncodedSnapshot[] => {
      world.step();
      const frame = frameOf(world);
      const shared = new SharedFrameWork();
      const out = encoders.map((enc) => enc.encode(frame, describe, shared));
      out.forEach((s, i) => expect(framesEqual(decoders[i].decode(s.bytes).frame, frame)).toBe(true));
      return out;
    };
    const first = sendAll();
    expect(first[1].bytes).toBe(first[0].bytes); // all full: encoded once
    encoders[0].acknowledge(1);
    encoders[1].acknowledge(1);
    const second = sendAll();
    expect(second[1].bytes).toBe(second[0].bytes); // same baseline (tick 1): the same bytes
    expect(second[2].bytes).not.toBe(second[0].bytes); // no ack yet: a full snapshot of its own
    expect(second[2].baselineTick).toBeNull();
    expect(second[0].baselineTick).toBe(1);
  });

  it('gives every client the same snapshots and descriptors with shared frame work as without it', () => {
    const world = new SyntheticWorld({ seed: 11, bodies: 12, spawnChance: 0.3, removeChance: 0.2 });
    const describe = (id: number) => world.describe(id);
    const alone = [0, 1, 2, 3].map(() => new SnapshotEncoder(format, { historySize: 8 }));
    const sharing = [0, 1, 2, 3].map(() => new SnapshotEncoder(format, { historySize: 8 }));
    for (const enc of [...alone, ...sharing]) enc.markDescriptorsKnown(world.bodies.map((b) => b.id));
    const rng = new Prng(12);
    let descriptorsSeen = 0;
    for (let t = 0; t < 120; t++) {
      world.step();
      const frame = frameOf(world);
      const work = new SharedFrameWork();
      for (let c = 0; c < 4; c++) {
        // Clients ack at different ticks (some never), so baselines and known descriptors differ between them.
        const ackTick = frame.tick - 1 - c * 2;
        if (c < 3 && ackTick > 0 && rng.nextU32() % 4 !== 0) {
          expect(sharing[c].acknowledge(ackTick)).toBe(alone[c].acknowledge(ackTick));
        }
        const a = alone[c].encode(frame, describe);
        const s = sharing[c].encode(frame, describe, work);
        expect(s.baselineTick).toBe(a.baselineTick);
        expect(s.bytes).toEqual(a.bytes);
        expect(s.descriptors.map((d) => d.id)).toEqual(a.descriptors.map((d) => d.id));
        descriptorsSeen += a.descriptors.length;
      }
    }
    expect(descriptorsSeen).toBeGreaterThan(0);
  });

  it('holds back repeated full snapshots while the first one awaits its ack', () => {
    const world = new SyntheticWorld({ seed: 6 });
    const enc = new SnapshotEncoder(format, { fullRetryTicks: 10 });
    expect(enc.shouldSend(1)).toBe(true);
    world.tick = 1;
    enc.encode(frameOf(world), (id) => world.describe(id));
    expect([enc.shouldSend(2), enc.shouldSend(10), enc.shouldSend(11)]).toEqual([false, false, true]);
    enc.acknowledge(1);
    expect(enc.shouldSend(2)).toBe(true);
  });

  it('never moves the baseline back on a late ack and ignores acks of ticks it never sent', () => {
    const world = new SyntheticWorld({ seed: 2 });
    const enc = new SnapshotEncoder(format);
    for (let i = 0; i < 5; i++) {
      world.step();
      enc.encode(frameOf(world), (id) => world.describe(id));
    }
    expect(enc.acknowledge(4)).toBe('baseline');
    expect(enc.acknowledge(2)).toBe('older');
    expect(enc.acknowledge(99)).toBe('unknown');
    expect(enc.baselineTick).toBe(4);
    expect(enc.stats.unknownAcks).toBe(1);
  });

  it('falls back to a full snapshot once the acked frame has left the history', () => {
    const world = new SyntheticWorld({ seed: 3 });
    const enc = new SnapshotEncoder(format, { historySize: 8 });
    world.step();
    enc.encode(frameOf(world), (id) => world.describe(id));
    enc.acknowledge(1);
    // Ticks 2..9 still find tick 1 among the last 8 snapshots sent; tick 10 does not.
    for (let i = 0; i < 8; i++) {
      world.step();
      expect(enc.encode(frameOf(world), (id) => world.describe(id)).baselineTick).toBe(1);
    }
    world.step();
    expect(enc.encode(frameOf(world), (id) => world.describe(id)).baselineTick).toBe(null);
    expect(enc.baselineTick).toBe(null);
  });

  it('resends a spawned body descriptor until a snapshot carrying it is acked, and never sends welcome bodies', () => {
    const world = new SyntheticWorld({ seed: 4, bodies: 5, spawnChance: 0, removeChance: 0 });
    const enc = new SnapshotEncoder(format);
    enc.markDescriptorsKnown(world.bodies.map((b) => b.id));
    const describe = (id: number) => world.describe(id);
    world.step();
    expect(enc.encode(frameOf(world), describe).descriptors).toEqual([]);
    enc.acknowledge(1);
    world.bodies.push({ id: 77, p: [0, 1, 0], q: [0, 0, 0, 1], active: true, kinematic: false });
    world.step();
    const carried = enc.encode(frameOf(world), describe);
    expect(carried.descriptors.map((d) => d.id)).toEqual([77]);
    world.step();
    expect(enc.encode(frameOf(world), describe).descriptors.map((d) => d.id)).toEqual([77]);
    enc.acknowledge(2);
    world.step();
    const after = enc.encode(frameOf(world), describe);
    expect(after.baselineTick).toBe(2);
    expect(after.descriptors).toEqual([]);
    // A full snapshot after a reset still skips descriptors the client holds.
    enc.reset();
    world.step();
    const full = enc.encode(frameOf(world), describe);
    expect(full.baselineTick).toBe(null);
    expect(full.descriptors).toEqual([]);
  });

  it('throws a clear error when the server has no descriptor for a spawned body', () => {
    const world = new SyntheticWorld({ seed: 5, bodies: 2 });
    const enc = new SnapshotEncoder(format);
    expect(() => enc.encode(frameOf(world), () => undefined)).toThrow(/no descriptor for spawned body 0/);
  });

  it('decodes exactly over a long stream with lost, delayed and reordered snapshots and acks', () => {
    // 4000 ticks, a snapshot every 2 ticks, 10% of snapshots and 30% of acks lost, delays of 2–30 ticks each way.
    const world = new SyntheticWorld({ seed: 31, bodies: 120, characters: 4 });
    const rng = new Prng(77);
    const enc = new SnapshotEncoder(format);
    const dec = new SnapshotDecoder(format);
    const truth = new TickHistory<QuantizedFrame>(400);
    const toClient: Array<{ at: number; s: EncodedSnapshot }> = [];
    const toServer: Array<{ at: number; tick: number }> = [];
    let decoded = 0;
    let baselineMisses = 0;
    const descriptors = new Set<number>(world.bodies.map((b) => b.id));
    enc.markDescriptorsKnown(descriptors);
    for (let t = 0; t < 4000; t++) {
      world.step();
      for (let i = toServer.length - 1; i >= 0; i--) {
        if (toServer[i].at <= t) {
          enc.acknowledge(toServer[i].tick);
          toServer.splice(i, 1);
        }
      }
      if (t % 2 === 0) {
        const frame = frameOf(world);
        truth.set(frame.tick, frame);
        const s = enc.encode(frame, (id) => world.describe(id));
        if (rng.next() >= 0.1) toClient.push({ at: t + rng.int(2, 30), s });
      }
      for (let i = 0; i < toClient.length; i++) {
        if (toClient[i].at > t) continue;
        const { s } = toClient.splice(i--, 1)[0];
        let got: QuantizedFrame;
        try {
          got = dec.decode(s.bytes).frame;
        } catch (e) {
          expect((e as Error).message).toMatch(/not in the decoder's history/);
          baselineMisses++;
          continue;
        }
        for (const d of s.descriptors) descriptors.add(d.id);
        expect(framesEqual(got, truth.get(s.tick)!)).toBe(true);
        // Every body the client can see has a descriptor it received.
        const undescribed = Array.from(got.bodyIds).filter((id) => !descriptors.has(id));
        expect(undescribed).toEqual([]);
        decoded++;
        if (rng.next() >= 0.3) toServer.push({ at: t + rng.int(2, 30), tick: s.tick });
      }
    }
    expect(decoded).toBeGreaterThan(1500);
    expect(enc.stats.delta).toBeGreaterThan(1500);
    // Baselines are acked frames, which the client decoded and still holds.
    expect(baselineMisses).toBe(0);
  });

  it('answers hostile raw snapshot frames mid-stream with a clear Error or a bounded frame, and keeps decoding the real ones', () => {
    // A client's path: the raw frame [18, bytes…] through decodeServerMessage, then SnapshotDecoder. Every fourth
    // snapshot of a real stream is followed by a mutated, cut or random copy.
    const world = new SyntheticWorld({ seed: 31, bodies: 300, characters: 3 });
    const enc = new SnapshotEncoder(format);
    const dec = new SnapshotDecoder(format);
    const rng = new Prng(77);
    const outcomes = { rejected: 0, decoded: 0 };
    for (let t = 0; t < 400; t++) {
      world.step();
      const frame = frameOf(world);
      const snap = enc.encode(frame, (id) => world.describe(id));
      const wire = encodeServerMessage({ type: 'snapshot', bytes: snap.bytes, descriptors: [] });
      const r = decodeServerMessage(wire);
      if (!r.ok || r.message.type !== 'snapshot') throw new Error('a real snapshot frame did not decode');
      expect(framesEqual(dec.decode(r.message.bytes).frame, frame)).toBe(true);
      enc.acknowledge(frame.tick);
      if (t % 4 !== 3) continue;
      const hostile = wire.slice(0, rng.int(1, wire.length + 8));
      if (hostile.length > wire.length) for (let i = wire.length; i < hostile.length; i++) hostile[i] = rng.int(0, 255);
      for (let k = rng.int(0, 4); k > 0; k--) hostile[rng.int(1, hostile.length - 1)] ^= 1 << rng.int(0, 7);
      const h = decodeServerMessage(hostile);
      if (!h.ok || h.message.type !== 'snapshot') {
        outcomes.rejected++;
        continue;
      }
      // Decoded against the real decoder's history without storing the result, so the real stream goes on.
      try {
        const got = decodeSnapshot(format, h.message.bytes, (tick) => dec.frame(tick), frame.tick);
        expect(got.bodies.length).toBe(got.bodyIds.length * 8);
        expect(got.bodyIds.length).toBeLessThanOrEqual(frame.bodyIds.length + hostile.length * 8);
        outcomes.decoded++;
      } catch (e) {
        expect(e).toBeInstanceOf(Error);
        expect((e as Error).message).toMatch(/snapshot|bit stream|range-coded/);
        outcomes.rejected++;
      }
    }
    expect(outcomes.rejected + outcomes.decoded).toBe(100);
    expect(outcomes.rejected).toBeGreaterThan(30);
  });

  it('keeps cubes-901 at 60 Hz under 128 kbps per client with acks one 100 ms round trip late', async () => {
    // 6 s of the bandwidth scene with a scripted driver: one full snapshot at the join, then deltas.
    const sim = await Simulation.create({ scenario: cubes901, seed: 1 });
    try {
      const fmt = createSnapshotFormat(cubes901.bounds);
      const enc = new SnapshotEncoder(fmt);
      enc.markDescriptorsKnown(sim.descriptors().filter((d) => d.motion !== 'static').map((d) => d.id));
      const dec = new SnapshotDecoder(fmt);
      const bots = new BotScript({ seed: 1, bots: 1, joinTicks: [0] });
      const acks: Array<{ at: number; tick: number }> = [];
      let bytes = 0;
      let afterJoin = 0;
      let mismatches = 0;
      for (let t = 0; t < 360; t++) {
        sim.step(bots.next());
        const tick = sim.tick;
        while (acks.length > 0 && acks[0].at <= tick) enc.acknowledge(acks.shift()!.tick);
        const frame = quantizeFrame(fmt, tick, sim.readBodyStates(), sim.characters());
        if (!enc.shouldSend(tick)) continue;
        const out = enc.encode(frame, (id) => sim.bodyDescriptor(id));
        if (!framesEqual(dec.decode(out.bytes).frame, frame)) mismatches++;
        // Payload plus the snapshot message's msgpack framing (5 bytes) and a WebSocket header (≤ 4 bytes).
        bytes += out.bytes.length + 9;
        if (tick > 60) afterJoin += out.bytes.length + 9;
        acks.push({ at: tick + 6, tick });
      }
      expect(mismatches).toBe(0);
      expect(frameBodies(sim)).toBeGreaterThan(900);
      expect((bytes * 8) / 6 / 1000).toBeLessThan(128);
      expect((afterJoin * 8) / 5 / 1000).toBeLessThan(128);
    } finally {
      sim.destroy();
    }
  });

  it('decodes a real Jolt stream of falling, spawning and removed bodies exactly', async () => {
    const world = await makeWorld({ maxBodies: 512 });
    try {
      world.addBox({ x: 60, y: 0.5, z: 60 }, { x: 0, y: -0.5, z: 0 }, null, { motion: 'static' });
      const rng = new Prng(8);
      for (let i = 0; i < 150; i++) {
        world.addBox({ x: 0.5, y: 0.5, z: 0.5 }, { x: rng.range(-10, 10), y: rng.range(1, 20), z: rng.range(-10, 10) }, null, {});
      }
      const enc = new SnapshotEncoder(format);
      const dec = new SnapshotDecoder(format);
      const inFlight: Array<{ frame: QuantizedFrame; s: EncodedSnapshot }> = [];
      let totalBytes = 0;
      for (let t = 1; t <= 240; t++) {
        world.stepFixed();
        if (t % 20 === 0) world.addSphere(0.4, { x: 0, y: 10, z: 0 }, {});
        if (t % 30 === 0) world.removeBody(world.bodyIds().find((id) => id > 5)!);
        const frame = quantizeFrame(format, t, world.readBodyStates(), []);
        const s = enc.encode(frame, (id) => ({ id, shape: world.getBody(id)!.shape!, color: [1, 1, 1], motion: 'dynamic', hidden: false, position: world.getBody(id)!.position(), rotation: world.getBody(id)!.rotation() }));
        totalBytes += s.bytes.length;
        inFlight.push({ frame, s });
        // Six ticks of latency: decode and ack the snapshot sent six ticks ago.
        if (inFlight.length > 6) {
          const old = inFlight.shift()!;
          expect(framesEqual(dec.decode(old.s.bytes).frame, old.frame)).toBe(true);
          enc.acknowledge(old.frame.tick);
        }
      }
      expect(enc.stats.delta).toBeGreaterThan(200);
      expect(totalBytes / 240).toBeLessThan(1500);
    } finally {
      world.destroy();
    }
  });
});

function frameBodies(sim: Simulation): number {
  return quantizeFrame(createSnapshotFormat(cubes901.bounds), sim.tick, sim.readBodyStates(), []).bodyIds.length;
}
