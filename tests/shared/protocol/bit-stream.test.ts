// Tests of the bit writer/reader: raw fields, Exp-Golomb codes, zigzag, order selection and truncation errors.
import { describe, expect, it } from 'vitest';
import { BitReader, BitWriter, bestExpGolombOrder, bitsFor, expGolombBits, unzigzag, zigzag } from '../../../shared/protocol/bit-stream.ts';
import { Prng } from '../../../shared/sim/prng.ts';

describe('bit-stream', () => {
  it('round-trips random raw fields of 1 to 32 bits', () => {
    const rng = new Prng(7);
    const fields: Array<[number, number]> = [];
    const w = new BitWriter(4);
    for (let i = 0; i < 5000; i++) {
      const bits = rng.int(1, 32);
      const value = bits === 32 ? rng.int(0, 0xffff_ffff) : rng.int(0, ((1 << bits) >>> 0) - 1);
      fields.push([value, bits]);
      w.writeBits(value, bits);
    }
    const bytes = w.finish();
    expect(bytes.length).toBe(Math.ceil(fields.reduce((n, [, b]) => n + b, 0) / 8));
    const r = new BitReader(bytes);
    for (const [value, bits] of fields) expect(r.readBits(bits)).toBe(value);
    expect(r.remainingBits).toBeLessThan(8);
  });

  it('round-trips Exp-Golomb codes of every order, including the largest value', () => {
    const rng = new Prng(11);
    const items: Array<[number, number]> = [];
    const w = new BitWriter();
    for (let i = 0; i < 4000; i++) {
      const k = rng.int(0, 15);
      const v = i % 97 === 0 ? 0x7fff_ffff : rng.next() < 0.5 ? rng.int(0, 40) : rng.int(0, 0x7fff_ffff);
      items.push([v, k]);
      w.writeExpGolomb(v, k);
    }
    const bitsBefore = w.bitLength;
    expect(bitsBefore).toBe(items.reduce((n, [v, k]) => n + expGolombBits(v, k), 0));
    const r = new BitReader(w.finish());
    for (const [v, k] of items) expect(r.readExpGolomb(k)).toBe(v);
  });

  it('lays out raw fields and Exp-Golomb codes bit for bit, least significant bit first, at every offset', () => {
    // Reference: one bit at a time (m zeros, a 1, the m low bits of value/2^k + 1, then the k low bits of value).
    const bits: number[] = [];
    const raw = (v: number, n: number): void => {
      for (let i = 0; i < n; i++) bits.push(Math.floor(v / 2 ** i) % 2);
    };
    const rng = new Prng(21);
    const w = new BitWriter(16);
    for (let i = 0; i < 3000; i++) {
      if (rng.next() < 0.5) {
        const n = rng.int(1, 32);
        const v = rng.int(0, 2 ** Math.min(n, 31) - 1) + (n === 32 && rng.next() < 0.5 ? 2 ** 31 : 0);
        w.writeBits(v, n);
        raw(v, n);
      } else {
        const k = rng.int(0, 20);
        const v = rng.next() < 0.3 ? rng.int(0, 0x7fff_ffff) : rng.int(0, 300);
        w.writeExpGolomb(v, k);
        const x1 = Math.floor(v / 2 ** k) + 1;
        const m = 31 - Math.clz32(x1);
        raw(0, m);
        raw(1, 1);
        raw(x1 - 2 ** m, m);
        raw(v % 2 ** k, k);
      }
    }
    expect(w.bitLength).toBe(bits.length);
    const expected = new Uint8Array(Math.ceil(bits.length / 8));
    bits.forEach((b, i) => (expected[i >> 3] |= b << (i & 7)));
    expect(w.finish()).toEqual(expected);
  });

  it('codes zero in one bit at order 0 and small signed deltas compactly', () => {
    const w = new BitWriter();
    w.writeExpGolomb(0, 0);
    expect(w.bitLength).toBe(1);
    w.writeSignedExpGolomb(-1, 0);
    w.writeSignedExpGolomb(1, 0);
    w.writeSignedExpGolomb(-300, 2);
    const r = new BitReader(w.finish());
    expect(r.readExpGolomb(0)).toBe(0);
    expect(r.readSignedExpGolomb(0)).toBe(-1);
    expect(r.readSignedExpGolomb(0)).toBe(1);
    expect(r.readSignedExpGolomb(2)).toBe(-300);
  });

  it('maps signed numbers through zigzag and back', () => {
    expect([0, -1, 1, -2, 2].map(zigzag)).toEqual([0, 1, 2, 3, 4]);
    for (let v = -1000; v <= 1000; v++) expect(unzigzag(zigzag(v))).toBe(v);
    expect(unzigzag(zigzag(-(2 ** 29)))).toBe(-(2 ** 29));
  });

  it('picks the Exp-Golomb order with the fewest total bits', () => {
    const small = [0, 1, 0, 2, 1, 0];
    expect(bestExpGolombOrder(small, small.length)).toBe(0);
    const large = Array.from({ length: 50 }, (_, i) => 1000 + i);
    const k = bestExpGolombOrder(large, large.length);
    const cost = (kk: number): number => large.reduce((n, v) => n + expGolombBits(v, kk), 0);
    for (let other = 0; other <= 15; other++) expect(cost(k)).toBeLessThanOrEqual(cost(other));
    expect(k).toBeGreaterThan(5);
  });

  it('throws a clear error when reading past the end', () => {
    const w = new BitWriter();
    w.writeBits(5, 3);
    const r = new BitReader(w.finish());
    r.readBits(8);
    expect(() => r.readBits(1)).toThrow(/truncated/);
    expect(() => new BitReader(new Uint8Array([0, 0, 0, 0, 0])).readExpGolomb(0)).toThrow(/prefix longer|truncated/);
  });

  it('refuses values that do not fit their field', () => {
    const w = new BitWriter();
    expect(() => w.writeBits(8, 3)).toThrow(/does not fit/);
    expect(() => w.writeBits(-1, 8)).toThrow(/unsigned/);
    expect(() => w.writeBits(1.5, 8)).toThrow(/unsigned/);
    expect(() => w.writeExpGolomb(2 ** 31, 0)).toThrow(/2\^31/);
  });

  it('counts the bits an integer range needs', () => {
    expect([0, 1, 2, 3, 4, 255, 256, 50000].map(bitsFor)).toEqual([0, 1, 2, 2, 3, 8, 9, 16]);
  });
});
