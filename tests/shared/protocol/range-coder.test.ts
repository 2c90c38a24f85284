// Tests of the adaptive range coder: every mix of modelled bits, plain bits and integer codes decodes to what was
// coded, skewed data costs fewer bits than plain, the flush is short, and reading past the end stops with an Error.
import { describe, expect, it } from 'vitest';
import { IntModel, newProbs, RangeDecoder, RangeEncoder, UIntModel } from '../../../shared/protocol/range-coder.ts';
import { Prng } from '../../../shared/sim/prng.ts';

type Op = { kind: 'bit' | 'direct' | 'uint' | 'int'; value: number };

function randomOps(rng: Prng, n: number): Op[] {
  const ops: Op[] = [];
  const skew = rng.next();
  for (let i = 0; i < n; i++) {
    const r = rng.int(0, 3);
    const bits = rng.int(0, 31);
    if (r === 0) ops.push({ kind: 'bit', value: rng.next() < skew ? 1 : 0 });
    else if (r === 1) ops.push({ kind: 'direct', value: Math.floor(rng.next() * 4294967296) });
    else if (r === 2) ops.push({ kind: 'uint', value: Math.min(0x7fff_ffff, Math.floor(rng.next() ** 4 * 2 ** bits)) });
    else ops.push({ kind: 'int', value: Math.floor((rng.next() - 0.5) * 2 ** Math.min(bits, 30)) });
  }
  return ops;
}

function encode(ops: Op[]): Uint8Array {
  const enc = new RangeEncoder();
  const probs = newProbs(2);
  const u = new UIntModel(2);
  const s = new IntModel(2);
  for (const op of ops) {
    if (op.kind === 'bit') enc.encodeBit(probs, 1, op.value);
    else if (op.kind === 'direct') enc.encodeDirect(op.value, 32);
    else if (op.kind === 'uint') u.encode(enc, op.value, op.value & 1);
    else s.encode(enc, op.value, 1);
  }
  return enc.finish();
}

function decode(bytes: Uint8Array, start: number, ops: Op[]): number[] {
  const dec = new RangeDecoder(bytes, start);
  const probs = newProbs(2);
  const u = new UIntModel(2);
  const s = new IntModel(2);
  return ops.map((op) => {
    if (op.kind === 'bit') return dec.decodeBit(probs, 1);
    if (op.kind === 'direct') return dec.decodeDirect(32);
    if (op.kind === 'uint') return u.decode(dec, op.value & 1);
    return s.decode(dec, 1);
  });
}

describe('range-coder', () => {
  it('decodes 2000 random mixes of modelled bits, plain bits and integers exactly, from any start offset', () => {
    const rng = new Prng(5);
    for (let trial = 0; trial < 2000; trial++) {
      const ops = randomOps(rng, rng.int(0, 60));
      const bytes = encode(ops);
      const offset = rng.int(0, 3);
      const framed = new Uint8Array(offset + bytes.length);
      framed.set(bytes, offset);
      expect(decode(framed, offset, ops)).toEqual(ops.map((o) => o.value));
    }
  });

  it('codes skewed bits in a fraction of a bit each and an empty stream in no bytes', () => {
    const ops: Op[] = Array.from({ length: 800 }, (_, i) => ({ kind: 'bit' as const, value: i % 40 === 0 ? 1 : 0 }));
    expect(encode(ops).length).toBeLessThan(800 / 8 / 3);
    expect(encode([]).length).toBe(0);
    expect(encode([{ kind: 'uint', value: 0 }]).length).toBeLessThanOrEqual(1);
  });

  it('codes small integers in fewer bytes than plain 32-bit fields', () => {
    const rng = new Prng(3);
    const ops: Op[] = Array.from({ length: 500 }, () => ({ kind: 'int' as const, value: rng.int(-20, 20) }));
    expect(encode(ops).length).toBeLessThan(500 * 6 / 8);
  });

  it('throws a clear Error once it reads past the end of the stream plus the flush allowance', () => {
    const dec = new RangeDecoder(new Uint8Array([0xff, 0x13]), 0);
    expect(() => {
      for (let i = 0; i < 100; i++) dec.decodeDirect(8);
    }).toThrow(/range-coded stream truncated/);
    const u = new UIntModel(1);
    expect(() => u.decode(new RangeDecoder(new Uint8Array([0xff, 0xff, 0xff, 0xff, 0xff, 0xff, 0xff, 0xff]), 0))).toThrow(/range-coded stream (corrupt|truncated)/);
  });

  it('refuses integers outside the codable range', () => {
    const enc = new RangeEncoder();
    expect(() => new UIntModel().encode(enc, -1)).toThrow(/UIntModel/);
    expect(() => new UIntModel().encode(enc, 2 ** 31)).toThrow(/UIntModel/);
  });
});
