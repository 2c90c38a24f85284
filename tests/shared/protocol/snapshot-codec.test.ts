// Tests of the snapshot bit layout: full and delta snapshots decode to the server's exact integers over long random
// streams (any baseline), unchanged bodies cost nothing, and truncated or corrupt bytes fail with clear errors.
import { describe, expect, it } from 'vitest';
import { createSnapshotFormat } from '../../../shared/protocol/quantization.ts';
import { decodeSnapshot, encodeSnapshot, readSnapshotHeader } from '../../../shared/protocol/snapshot-codec.ts';
import { framesEqual, quantizeFrame, type QuantizedFrame } from '../../../shared/protocol/snapshot-frame.ts';
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
    expect(readSnapshotHeader(bytes)).toEqual({ tick: 1, baselineTick: null, bodyCount: frame.bodyIds.length, characterCount: 6 });
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
      const decoded = decodeSnapshot(format, bytes, (tick) => frames.get(tick));
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
    expect(delta.length).toBeLessThanOrEqual(10);
    expect(framesEqual(decodeSnapshot(format, delta, () => a), b)).toBe(true);
  });

  it('costs a few bytes per moved body in a delta', () => {
    const world = new SyntheticWorld({ seed: 6, bodies: 1000, characters: 0, moveChance: 0, spawnChance: 0, removeChance: 0, sleepChance: 0, joinChance: 0 });
    const a = frameOf(world);
    for (const i of [10, 400, 800]) world.bodies[i].p[1] -= 0.05;
    world.tick++;
    const b = frameOf(world);
    const delta = encodeSnapshot(format, b, a);
    expect(delta.length).toBeLessThan(30);
    expect(framesEqual(decodeSnapshot(format, delta, () => a), b)).toBe(true);
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
    expect(() => decodeSnapshot(format, bytes, () => undefined)).toThrow(/baseline tick 0 is not in the decoder's history/);
  });

  it('fails with a clear Error at every truncation point and on corrupt bits, never with anything else', () => {
    const world = new SyntheticWorld({ seed: 12, bodies: 60, characters: 3 });
    const a = frameOf(world);
    for (let i = 0; i < 5; i++) world.step();
    const b = frameOf(world);
    const bytes = encodeSnapshot(format, b, a);
    for (let len = 0; len < bytes.length; len++) {
      expect(() => decodeSnapshot(format, bytes.subarray(0, len), () => a)).toThrow(Error);
    }
    const rng = new Prng(1);
    let rejected = 0;
    for (let trial = 0; trial < 2000; trial++) {
      const bad = bytes.slice();
      const bit = rng.int(33, bad.length * 8 - 1);
      bad[bit >> 3] ^= 1 << (bit & 7);
      try {
        // A flip may still parse (a changed value, or an unused Exp-Golomb order): then it is a well-formed frame.
        const decoded = decodeSnapshot(format, bad, () => a);
        expect(decoded.bodies.length).toBe(decoded.bodyIds.length * 8);
      } catch (e) {
        expect(e).toBeInstanceOf(Error);
        expect((e as Error).message).toMatch(/snapshot|bit stream/);
        rejected++;
      }
    }
    expect(rejected).toBeGreaterThan(0);
  });
});
