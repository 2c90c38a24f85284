// An adaptive binary range coder (the LZMA scheme: 11-bit probabilities, 32-bit range, carry through a cached byte)
// and the integer codes the snapshot codec builds on it. Integer arithmetic only, so both ends stay bit-identical in
// every runtime. The decoder is total: reading more than FLUSH_BYTES past the end throws, so hostile bytes cost at most
// their own length in work.

const PROB_BITS = 11;
const PROB_ONE = 1 << PROB_BITS;
const PROB_INIT = PROB_ONE >>> 1;
/**
 * Adaptation speed by how many bits a context has coded: its first bits move the probability far (statistics start
 * afresh in every snapshot, which holds only some hundred symbols), later ones 1/16 of the way.
 */
const RATE_SHIFTS = [2, 2, 3, 3, 3, 3, 4, 4, 4, 4, 4, 4, 5];
const COUNT_SHIFT = 12;
const PROB_MASK = (1 << COUNT_SHIFT) - 1;
const MAX_COUNT = RATE_SHIFTS.length - 1;
/** 2^0 … 2^32, exact. */
const POW2 = new Float64Array(33);
POW2[0] = 1;
for (let i = 1; i < POW2.length; i++) POW2[i] = POW2[i - 1] * 2;
const TOP = 1 << 24;
const TWO_POW_32 = 4294967296;
/** Bytes the decoder may read past the end: the flush trims at most this many trailing zero bytes. */
const FLUSH_BYTES = 4;
/** Longest Exp-Golomb bucket: values below 2^31. */
const MAX_BUCKET = 31;
/** Mantissa bits (after the leading one) that are modelled; lower ones are sent as plain bits. */
const MODELLED_MANTISSA_BITS = 2;

/** Moves a context's probability of a 0 towards what was coded; the state packs (bits coded) << 12 | probability. */
function adapt(state: number, bit: number): number {
  const n = state >>> COUNT_SHIFT;
  const p = state & PROB_MASK;
  const shift = RATE_SHIFTS[n];
  const next = bit === 0 ? p + ((PROB_ONE - p) >>> shift) : p - (p >>> shift);
  return ((n < MAX_COUNT ? n + 1 : n) << COUNT_SHIFT) | next;
}

/** Probabilities for `count` binary contexts, each starting at ½. */
export function newProbs(count: number): Uint16Array {
  return new Uint16Array(count).fill(PROB_INIT);
}

/** Sets every context of `probs` back to ½ (statistics reused across snapshots start afresh in each). */
export function resetProbs(probs: Uint16Array): void {
  probs.fill(PROB_INIT);
}

/** Encodes bits under adaptive probabilities into bytes. */
export class RangeEncoder {
  private low = 0;
  private range = 0xffff_ffff;
  private cache = 0;
  private cacheSize = 1;
  private first = true;
  private out: Uint8Array;
  private pos = 0;

  constructor(initialBytes = 64) {
    this.out = new Uint8Array(Math.max(16, initialBytes));
  }

  private put(byte: number): void {
    // The very first byte of the LZMA scheme is always 0: it is not sent, and the decoder starts one byte later.
    if (this.first) {
      this.first = false;
      return;
    }
    if (this.pos === this.out.length) {
      const next = new Uint8Array(this.out.length * 2);
      next.set(this.out);
      this.out = next;
    }
    this.out[this.pos++] = byte;
  }

  private shiftLow(): void {
    if (this.low < 0xff00_0000 || this.low >= TWO_POW_32) {
      const carry = this.low >= TWO_POW_32 ? 1 : 0;
      let temp = this.cache;
      do {
        this.put((temp + carry) & 0xff);
        temp = 0xff;
      } while (--this.cacheSize !== 0);
      this.cache = Math.floor(this.low / TOP) & 0xff;
    }
    this.cacheSize++;
    this.low = (this.low % TOP) * 256;
  }

  /** Codes one bit under probs[i] (the probability of a 0, in 1/2048) and adapts it. */
  encodeBit(probs: Uint16Array, i: number, bit: number): void {
    const state = probs[i];
    const p = state & PROB_MASK;
    const bound = (this.range >>> PROB_BITS) * p;
    probs[i] = adapt(state, bit);
    if (bit === 0) this.range = bound;
    else {
      this.low += bound;
      this.range -= bound;
    }
    while (this.range < TOP) {
      this.range = (this.range * 256) >>> 0;
      this.shiftLow();
    }
  }

  /** Codes the low `count` (0–32) bits of an unsigned value at probability ½ each, most significant first. */
  encodeDirect(value: number, count: number): void {
    for (let b = count - 1; b >= 0; b--) {
      this.range = this.range >>> 1;
      if (((value >>> b) & 1) === 1) this.low += this.range;
      while (this.range < TOP) {
        this.range = (this.range * 256) >>> 0;
        this.shiftLow();
      }
    }
  }

  /** Ends the stream with as few bytes as decode to the same bits (the decoder reads zeros past the end). */
  finish(): Uint8Array {
    // The value with the most trailing zero bits inside [low, low + range).
    for (let s = 32; s >= 0; s--) {
      const unit = POW2[s];
      const v = Math.ceil(this.low / unit) * unit;
      if (v < this.low + this.range) {
        this.low = v;
        break;
      }
    }
    for (let i = 0; i < 5; i++) this.shiftLow();
    let end = this.pos;
    while (end > 0 && end > this.pos - FLUSH_BYTES && this.out[end - 1] === 0) end--;
    return this.out.slice(0, end);
  }
}

/** Decodes what a RangeEncoder wrote, from `bytes[start..]`; throws a clear Error past the end of the stream. */
export class RangeDecoder {
  private readonly bytes: Uint8Array;
  private pos: number;
  private range = 0xffff_ffff;
  private code = 0;

  constructor(bytes: Uint8Array, start: number) {
    this.bytes = bytes;
    this.pos = start;
    for (let i = 0; i < 4; i++) this.code = this.code * 256 + this.next();
  }

  private next(): number {
    const p = this.pos++;
    if (p < this.bytes.length) return this.bytes[p];
    if (p >= this.bytes.length + FLUSH_BYTES) throw new Error(`range-coded stream truncated: read past byte ${this.bytes.length}`);
    return 0;
  }

  /** Whether the decoder has read past the last byte by more than a flush trims (so more data was expected). */
  get overrunBytes(): number {
    return Math.max(0, this.pos - this.bytes.length);
  }

  /** Decodes one bit under probs[i] and adapts it as the encoder did. */
  decodeBit(probs: Uint16Array, i: number): number {
    const state = probs[i];
    const bound = (this.range >>> PROB_BITS) * (state & PROB_MASK);
    let bit: number;
    if (this.code < bound) {
      this.range = bound;
      bit = 0;
    } else {
      this.code -= bound;
      this.range -= bound;
      bit = 1;
    }
    probs[i] = adapt(state, bit);
    while (this.range < TOP) {
      this.range = (this.range * 256) >>> 0;
      this.code = ((this.code * 256) % TWO_POW_32) + this.next();
    }
    return bit;
  }

  /** Decodes `count` (0–32) bits coded with encodeDirect. */
  decodeDirect(count: number): number {
    let value = 0;
    for (let b = 0; b < count; b++) {
      this.range = this.range >>> 1;
      let bit = 0;
      if (this.code >= this.range) {
        this.code -= this.range;
        bit = 1;
      }
      value = value * 2 + bit;
      while (this.range < TOP) {
        this.range = (this.range * 256) >>> 0;
        this.code = ((this.code * 256) % TWO_POW_32) + this.next();
      }
    }
    return value;
  }
}

/**
 * Adaptive Exp-Golomb codes for unsigned integers below 2^31 under `contexts` separate statistics: the bucket
 * (bit length of value + 1) in unary with one probability per step, the top mantissa bits modelled per bucket, the
 * rest plain. Small values cost a fraction of a bit when they are common.
 */
export class UIntModel {
  readonly contexts: number;
  private readonly bucketProbs: Uint16Array;
  private readonly mantissaProbs: Uint16Array;

  constructor(contexts = 1) {
    this.contexts = contexts;
    this.bucketProbs = newProbs(contexts * (MAX_BUCKET + 1));
    this.mantissaProbs = newProbs(contexts * (MAX_BUCKET + 1) * (1 << MODELLED_MANTISSA_BITS));
  }

  /** Forgets the statistics (every probability back to ½). */
  reset(): void {
    this.bucketProbs.fill(PROB_INIT);
    this.mantissaProbs.fill(PROB_INIT);
  }

  /** The bucket of a value: 0 for 0, else the bit length of value + 1 minus one. */
  static bucket(value: number): number {
    return 31 - Math.clz32(value + 1);
  }

  encode(enc: RangeEncoder, value: number, ctx = 0): void {
    if (!Number.isInteger(value) || value < 0 || value > 0x7fff_ffff) throw new Error(`UIntModel: need 0..2^31-1, got ${value}`);
    const x = value + 1;
    const m = 31 - Math.clz32(x);
    const base = ctx * (MAX_BUCKET + 1);
    for (let j = 0; j < m; j++) enc.encodeBit(this.bucketProbs, base + j, 1);
    if (m < MAX_BUCKET) enc.encodeBit(this.bucketProbs, base + m, 0);
    // The m bits below x's leading one: the top ones through a small binary tree per bucket.
    const modelled = m < MODELLED_MANTISSA_BITS ? m : MODELLED_MANTISSA_BITS;
    let node = 1;
    const treeBase = (base + m) << MODELLED_MANTISSA_BITS;
    for (let b = m - 1; b >= m - modelled; b--) {
      const bit = (x >>> b) & 1;
      enc.encodeBit(this.mantissaProbs, treeBase + node, bit);
      node = (node << 1) | bit;
    }
    const rest = m - modelled;
    if (rest > 0) enc.encodeDirect(x & ((1 << rest) - 1), rest);
  }

  decode(dec: RangeDecoder, ctx = 0): number {
    const base = ctx * (MAX_BUCKET + 1);
    let m = 0;
    while (m < MAX_BUCKET && dec.decodeBit(this.bucketProbs, base + m) === 1) m++;
    const modelled = m < MODELLED_MANTISSA_BITS ? m : MODELLED_MANTISSA_BITS;
    let node = 1;
    const treeBase = (base + m) << MODELLED_MANTISSA_BITS;
    for (let b = 0; b < modelled; b++) node = (node << 1) | dec.decodeBit(this.mantissaProbs, treeBase + node);
    const rest = m - modelled;
    // node holds x's leading one and its modelled bits.
    const x = node * POW2[rest] + (rest > 0 ? dec.decodeDirect(rest) : 0);
    const value = x - 1;
    if (value > 0x7fff_ffff) throw new Error(`range-coded stream corrupt: integer ${value} out of range`);
    return value;
  }
}

/** Signed integers: the magnitude through a UIntModel, then a modelled sign bit when it is not zero. */
export class IntModel {
  private readonly magnitude: UIntModel;
  private readonly signProbs: Uint16Array;

  constructor(contexts = 1) {
    this.magnitude = new UIntModel(contexts);
    this.signProbs = newProbs(contexts);
  }

  /** Forgets the statistics. */
  reset(): void {
    this.magnitude.reset();
    this.signProbs.fill(PROB_INIT);
  }

  encode(enc: RangeEncoder, value: number, ctx = 0): void {
    const a = value < 0 ? -value : value;
    this.magnitude.encode(enc, a, ctx);
    if (a !== 0) enc.encodeBit(this.signProbs, ctx, value < 0 ? 1 : 0);
  }

  decode(dec: RangeDecoder, ctx = 0): number {
    const a = this.magnitude.decode(dec, ctx);
    if (a === 0) return 0;
    return dec.decodeBit(this.signProbs, ctx) === 1 ? -a : a;
  }
}
