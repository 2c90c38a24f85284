// Tests of the snapshot layout: full and delta snapshots decode to the server's exact integers over long random
// streams (any baseline), unchanged bodies cost nothing, delta ticks are completed from the receiver's newest tick,
// and truncated, corrupt or random bytes fail with clear errors or decode to a well-formed frame, within bounded work.
import { describe, expect, it } from 'vitest';
import { createSnapshotFormat } from '../../../shared/protocol/quantization.ts';
import { completeTick, decodeSnapshot, encodeSnapshot, MAX_BASELINE_AGE, readSnapshotHeader } from '../../../shared/protocol/snapshot-codec.ts';
import { emptyFrame, framesEqual, quantizeFrame, type QuantizedFrame } from '../../../shared/protocol/snapshot-frame.ts';
import { Prng } from '../../../shared/sim/prng.ts';
import { SYNTH_BOUNDS, SyntheticWorld } from './synthetic-world.ts';

const format = createSnapshotFormat(SYNTH_BOUNDS);

function frameOf(world: SyntheticWorld): QuantizedFrame {
  return quantizeFrame(format, world.tick, world.read(), world.characterStates());
}

describe('snapshot-codec', () => {
  it('decodes a full snapshot to the exact frame', () => {
    const world = new SyntheticWorld({ seed: 2, bodies: 500, characters: 6 });
    world.step();
    const frame = frameOf(world);
    const bytes = encodeSnapshot(format, frame, null);
    expect(readSnapshotHeader(bytes)).toEqual({ tick: 1, baselineTick: null, bodiesChanged: true, charactersChanged: true, payloadOffset: 5 });
    expect(framesEqual(decodeSnapshot(format, bytes, () => undefined), frame)).toBe(true);
  });

  it('reproduces every frame bit for bit over 3000 ticks against randomly chosen baselines', () => {
    const world = new SyntheticWorld({ seed: 21, bodies: 150, characters: 4 });
    const rng = new Prng(99);
    const frames = new Map<number, QuantizedFrame>();
    let deltas = 0;
    for (let t = 0; t < 3000; t++) {
      world.step();
      const frame = frameOf(world);
      const older = [...frames.keys()];
      const baseline = older.length > 0 && rng.next() < 0.85 ? frames.get(older[rng.int(Math.max(0, older.length - 70), older.length - 1)])! : null;
      if (baseline) deltas++;
      const bytes = encodeSnapshot(format, frame, baseline);
      const decoded = decodeSnapshot(format, bytes, (tick) => frames.get(tick), frame.tick - 1);
      expect(framesEqual(decoded, frame)).toBe(true);
      frames.set(frame.tick, decoded);
      if (frames.size > 80) frames.delete(frames.keys().next().value!);
    }
    expect(deltas).toBeGreaterThan(2000);
  });

  it('sends only changed bodies: an unchanged world of 1000 bodies costs a few bytes', () => {
    const world = new SyntheticWorld({ seed: 5, bodies: 1000, characters: 2 });
    const a = frameOf(world);
    world.tick++;
    const b = frameOf(world);
    const full = encodeSnapshot(format, b, null);
    const delta = encodeSnapshot(format, b, a);
    expect(full.length).toBeGreaterThan(8000);
    // Header only: the delta flag, 16 tick bits, the baseline age and two "nothing changed" bits.
    expect(delta.length).toBe(3);
    expect(framesEqual(decodeSnapshot(format, delta, () => a, a.tick), b)).toBe(true);
  });

  it('costs a few bytes per moved body in a delta', () => {
    const world = new SyntheticWorld({ seed: 6, bodies: 1000, characters: 0, moveChance: 0, spawnChance: 0, removeChance: 0, sleepChance: 0, joinChance: 0 });
    const a = frameOf(world);
    for (const i of [10, 400, 800]) world.bodies[i].p[1] -= 0.05;
    world.tick++;
    const b = frameOf(world);
    const delta = encodeSnapshot(format, b, a);
    expect(delta.length).toBeLessThan(24);
    expect(framesEqual(decodeSnapshot(format, delta, () => a, a.tick), b)).toBe(true);
  });

  it('refuses a baseline that is not older than the frame', () => {
    const world = new SyntheticWorld({ seed: 3 });
    const f = frameOf(world);
    expect(() => encodeSnapshot(format, f, f)).toThrow(/older/);
  });

  it('names the missing baseline when the decoder does not hold it', () => {
    const world = new SyntheticWorld({ seed: 3 });
    const a = frameOf(world);
    world.step();
    const bytes = encodeSnapshot(format, frameOf(world), a);
    expect(() => decodeSnapshot(format, bytes, () => undefined, 0)).toThrow(/baseline tick 0 is not in the decoder's history/);
    expect(() => decodeSnapshot(format, bytes, () => a)).toThrow(/needs the newest decoded tick/);
  });

  it('completes a delta tick from the newest tick the receiver decoded across the 16-bit wrap, in order or delayed', () => {
    const tick = 5 * 65536 + 3;
    const bytes = encodeSnapshot(format, emptyFrame(tick), emptyFrame(tick - 9));
    expect(readSnapshotHeader(bytes, tick - 1)).toMatchObject({ tick, baselineTick: tick - 9 });
    expect(readSnapshotHeader(bytes, tick - 9)).toMatchObject({ tick, baselineTick: tick - 9 });
    // Delayed behind newer snapshots: the nearest tick with those low bits.
    expect(readSnapshotHeader(bytes, tick + 500)).toMatchObject({ tick });
    expect(completeTick(5, 0)).toBe(5);
    expect(completeTick(65535, 2)).toBe(65535);
    expect(completeTick(1, 65534)).toBe(65537);
  });

  it('refuses a baseline further back than a 16-bit tick can reach', () => {
    expect(() => encodeSnapshot(format, emptyFrame(MAX_BASELINE_AGE + 1), emptyFrame(0))).toThrow(/more than/);
    expect(encodeSnapshot(format, emptyFrame(MAX_BASELINE_AGE), emptyFrame(0)).length).toBeLessThan(8);
  });

  it('fails with a clear Error at every truncation point and on corrupt bits, never with anything else', () => {
    const world = new SyntheticWorld({ seed: 12, bodies: 60, characters: 3 });
    const a = frameOf(world);
    for (let i = 0; i < 5; i++) world.step();
    const b = frameOf(world);
    const bytes = encodeSnapshot(format, b, a);
    // The range coder reads zeros past the end (its flush trims them): a cut snapshot fails or decodes to another frame.
    let cutRejected = 0;
    for (let len = 0; len < bytes.length; len++) {
      try {
        const decoded = decodeSnapshot(format, bytes.subarray(0, len), () => a, a.tick);
        expect(framesEqual(decoded, b)).toBe(false);
      } catch (e) {
        expect((e as Error).message).toMatch(/snapshot|bit stream|range-coded/);
        cutRejected++;
      }
    }
    expect(cutRejected).toBeGreaterThan(bytes.length / 2);
    const rng = new Prng(1);
    let rejected = 0;
    for (let trial = 0; trial < 2000; trial++) {
      const bad = bytes.slice();
      const bit = rng.int(33, bad.length * 8 - 1);
      bad[bit >> 3] ^= 1 << (bit & 7);
      try {
        // A flip may still parse (a changed value, or an unused Exp-Golomb order): then it is a well-formed frame.
        const decoded = decodeSnapshot(format, bad, () => a, a.tick);
        expect(decoded.bodies.length).toBe(decoded.bodyIds.length * 8);
      } catch (e) {
        expect(e).toBeInstanceOf(Error);
        expect((e as Error).message).toMatch(/snapshot|bit stream|range-coded/);
        rejected++;
      }
    }
    expect(rejected).toBeGreaterThan(0);
  });

  it('turns random bytes against a 1000-body baseline into a clear Error or a bounded well-formed frame', () => {
    const world = new SyntheticWorld({ seed: 14, bodies: 1000, characters: 4 });
    const a = frameOf(world);
    const rng = new Prng(7);
    let rejected = 0;
    for (let trial = 0; trial < 3000; trial++) {
      const bytes = new Uint8Array(rng.int(0, 48));
      for (let i = 0; i < bytes.length; i++) bytes[i] = rng.int(0, 255);
      try {
        const decoded = decodeSnapshot(format, bytes, (t) => (t === a.tick ? a : undefined), a.tick + rng.int(0, 5));
        expect(decoded.bodies.length).toBe(decoded.bodyIds.length * 8);
        // What random bytes can add is bounded by their length, whatever they claim.
        expect(decoded.bodyIds.length).toBeLessThanOrEqual(a.bodyIds.length + bytes.length * 8);
        expect(decoded.playerIds.length).toBeLessThanOrEqual(a.playerIds.length + bytes.length * 8);
      } catch (e) {
        expect(e).toBeInstanceOf(Error);
        expect((e as Error).message).toMatch(/snapshot|bit stream|range-coded/);
        rejected++;
      }
    }
    expect(rejected).toBeGreaterThan(2000);
  });
});
