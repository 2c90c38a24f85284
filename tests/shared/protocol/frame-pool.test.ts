// Tests of shared/protocol/frame-pool.ts: a pooled frame's buffer is reused only after its last holder let go, a
// frame whose buffer went back reads as dead, and an encoder never deltas against a dead baseline.
import { describe, expect, it } from 'vitest';
import { frameIsLive, QuantizedFramePool } from '../../../shared/protocol/frame-pool.ts';
import { createSnapshotFormat } from '../../../shared/protocol/quantization.ts';
import { framesEqual, quantizeFrame, type QuantizedFrame } from '../../../shared/protocol/snapshot-frame.ts';
import { SnapshotDecoder, SnapshotEncoder } from '../../../shared/protocol/snapshot-stream.ts';
import { SYNTH_BOUNDS, SyntheticWorld } from './synthetic-world.ts';

const format = createSnapshotFormat(SYNTH_BOUNDS);

describe('QuantizedFramePool', () => {
  it('hands a buffer out again only after every holder of its frame released it', () => {
    const pool = new QuantizedFramePool();
    const a = pool.take(10, 2);
    a.lease.retain();
    a.lease.retain();
    a.lease.release();
    const b = pool.take(10, 2);
    expect(b.bodies.buffer).not.toBe(a.bodies.buffer);
    a.lease.release();
    const c = pool.take(10, 2);
    expect(c.bodies.buffer).toBe(a.bodies.buffer);
    expect(pool.counts).toEqual({ taken: 3, reused: 1 });
  });

  it('gives exactly sized views, and a new buffer when a kept one is too small', () => {
    const pool = new QuantizedFramePool();
    const a = pool.take(3, 1);
    expect([a.bodyIds.length, a.bodies.length, a.playerIds.length, a.characters.length]).toEqual([3, 24, 1, 11]);
    a.lease.retain();
    a.lease.release();
    const big = pool.take(500, 1);
    expect(big.bodies.buffer).not.toBe(a.bodies.buffer);
    expect(big.bodyIds.length).toBe(500);
  });

  it('marks a frame dead once its buffer went back, and refuses a release without a retain', () => {
    const world = new SyntheticWorld({ seed: 3, bodies: 20 });
    world.step();
    const pool = new QuantizedFramePool();
    const frame = quantizeFrame(format, world.tick, world.read(), world.characterStates(), { pool });
    expect(() => frame.lease!.release()).toThrow(/without a matching retain/);
    frame.lease!.retain();
    expect(frameIsLive(frame)).toBe(true);
    frame.lease!.release();
    expect(frameIsLive(frame)).toBe(false);
    expect(frameIsLive(quantizeFrame(format, world.tick, world.read(), world.characterStates()))).toBe(true);
  });

  it('makes an encoder send a full snapshot when its baseline was given back too early and its buffer reused', () => {
    // A holder that lets go too soon must cost a full snapshot, never a delta against another tick's numbers.
    const world = new SyntheticWorld({ seed: 5, bodies: 30, moveChance: 0.9 });
    const pool = new QuantizedFramePool();
    const encoder = new SnapshotEncoder(format);
    const decoder = new SnapshotDecoder(format);
    const frameNow = (): QuantizedFrame => quantizeFrame(format, world.tick, world.read(), world.characterStates(), { pool });
    world.step();
    const first = frameNow();
    decoder.decode(encoder.encode(first, (id) => world.describe(id)).bytes);
    encoder.acknowledge(first.tick);
    // The encoder holds `first` twice (history and previous frame): both let go behind its back.
    first.lease!.release();
    first.lease!.release();
    world.step();
    const second = frameNow(); // takes `first`'s buffer and overwrites it
    expect(second.bodies.buffer).toBe(first.bodies.buffer);
    const expected = quantizeFrame(format, world.tick, world.read(), world.characterStates());
    const sent = encoder.encode(second, (id) => world.describe(id));
    expect(sent.baselineTick).toBeNull();
    expect(framesEqual(decoder.decode(sent.bytes).frame, expected)).toBe(true);
  });
});
