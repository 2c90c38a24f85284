// Bit-level writer and reader over Uint8Array for the snapshot codec: raw fields of 0–32 bits, Exp-Golomb codes for
// small unsigned numbers, zigzag for signed deltas. Bits fill each byte from its least significant bit upwards.

const TWO_POW_32 = 4294967296;

/** Grows a byte buffer and appends bit fields to it. */
export class BitWriter {
  private buf: Uint8Array;
  private bitPos = 0;

  constructor(initialBytes = 256) {
    this.buf = new Uint8Array(Math.max(16, initialBytes));
  }

  /** Bits written so far. */
  get bitLength(): number {
    return this.bitPos;
  }

  private grow(needBytes: number): void {
    let cap = this.buf.length * 2;
    while (cap < needBytes) cap *= 2;
    const next = new Uint8Array(cap);
    next.set(this.buf);
    this.buf = next;
  }

  /** Appends the low `count` bits (0–32) of an unsigned integer value. */
  writeBits(value: number, count: number): void {
    if (count === 0) return;
    if (!(count > 0 && count <= 32) || !Number.isInteger(value) || value < 0 || value >= TWO_POW_32) {
      throw new Error(`BitWriter.writeBits: need an unsigned integer and 1..32 bits, got ${value} in ${count} bits`);
    }
    if (count < 32 && value >= (1 << count) >>> 0) throw new Error(`BitWriter.writeBits: ${value} does not fit in ${count} bits`);
    const pos = this.bitPos;
    const needBytes = (pos + count + 7) >>> 3;
    if (needBytes > this.buf.length) this.grow(needBytes);
    const buf = this.buf;
    let byteIndex = pos >>> 3;
    const offset = pos & 7;
    this.bitPos = pos + count;
    // The value has no bits above `count`, and bytes past the write position are still zero.
    buf[byteIndex] |= (value << offset) & 0xff;
    const first = 8 - offset;
    if (count <= first) return;
    let v = (value >>> 0) >>> first;
    for (let n = count - first; n > 0; n -= 8) {
      buf[++byteIndex] = v & 0xff;
      v >>>= 8;
    }
  }

  /** Appends one bit. */
  writeBool(flag: boolean): void {
    this.writeBits(flag ? 1 : 0, 1);
  }

  /** Appends an unsigned integer (< 2^31) as an Exp-Golomb code of order k (0–20): small values take few bits. */
  writeExpGolomb(value: number, k: number): void {
    if (!Number.isInteger(value) || value < 0 || value > 0x7fff_ffff) throw new Error(`BitWriter.writeExpGolomb: need 0..2^31-1, got ${value}`);
    const high = Math.floor(value / ((1 << k) >>> 0));
    const low = value - high * ((1 << k) >>> 0);
    const x1 = high + 1;
    const m = 31 - Math.clz32(x1);
    // m zeros, a terminating 1 (x1's top bit), x1's m lower bits, then the k low bits of the value.
    const prefixBits = 2 * m + 1;
    if (prefixBits + k <= 32) {
      // One field, least significant bit first: the same bits as the four writes below (prefixBits is odd, ≤ 31).
      const prefix = ((1 << m) >>> 0) + (x1 - ((1 << m) >>> 0)) * ((1 << (m + 1)) >>> 0);
      this.writeBits(prefix + low * ((1 << prefixBits) >>> 0), prefixBits + k);
      return;
    }
    this.writeBits(0, m);
    this.writeBits(1, 1);
    this.writeBits(x1 - ((1 << m) >>> 0), m);
    this.writeBits(low, k);
  }

  /** Appends a signed integer (|v| < 2^30) as a zigzag-mapped Exp-Golomb code of order k. */
  writeSignedExpGolomb(value: number, k: number): void {
    this.writeExpGolomb(zigzag(value), k);
  }

  /** The bytes written (a copy sized to the content; the unused bits of the last byte are zero). */
  finish(): Uint8Array {
    return this.buf.slice(0, (this.bitPos + 7) >>> 3);
  }
}

/** Reads bit fields back from bytes a BitWriter produced; every read past the end throws a clear Error. */
export class BitReader {
  private readonly buf: Uint8Array;
  private bitPos = 0;
  private readonly bitEnd: number;

  constructor(bytes: Uint8Array) {
    this.buf = bytes;
    this.bitEnd = bytes.length * 8;
  }

  /** Bits consumed so far. */
  get bitPosition(): number {
    return this.bitPos;
  }

  /** Bits left. */
  get remainingBits(): number {
    return this.bitEnd - this.bitPos;
  }

  /** Reads `count` (0–32) bits as an unsigned integer. */
  readBits(count: number): number {
    if (count === 0) return 0;
    if (this.bitPos + count > this.bitEnd) {
      throw new Error(`bit stream truncated: need ${count} bits at bit ${this.bitPos}, have ${this.bitEnd - this.bitPos}`);
    }
    let result = 0;
    let shift = 0;
    let n = count;
    const buf = this.buf;
    while (n > 0) {
      const byteIndex = this.bitPos >>> 3;
      const bitOffset = this.bitPos & 7;
      const take = Math.min(8 - bitOffset, n);
      const bits = (buf[byteIndex] >>> bitOffset) & ((1 << take) - 1);
      result += bits * ((1 << shift) >>> 0);
      this.bitPos += take;
      shift += take;
      n -= take;
    }
    return result;
  }

  /** Reads one bit. */
  readBool(): boolean {
    return this.readBits(1) === 1;
  }

  /** Reads an Exp-Golomb code of order k. */
  readExpGolomb(k: number): number {
    let m = 0;
    while (this.readBits(1) === 0) {
      m++;
      if (m > 31) throw new Error(`bit stream corrupt: Exp-Golomb prefix longer than 31 bits at bit ${this.bitPos}`);
    }
    // The terminating 1 was x1's top bit; its m lower bits follow.
    const rest = this.readBits(m);
    const x1 = ((1 << m) >>> 0) + rest;
    const high = x1 - 1;
    const low = this.readBits(k);
    const value = high * ((1 << k) >>> 0) + low;
    if (value > 0x7fff_ffff) throw new Error(`bit stream corrupt: Exp-Golomb value ${value} out of range`);
    return value;
  }

  /** Reads a zigzag-mapped signed Exp-Golomb code of order k. */
  readSignedExpGolomb(k: number): number {
    return unzigzag(this.readExpGolomb(k));
  }
}

/** Maps signed to unsigned: 0, -1, 1, -2, 2 … → 0, 1, 2, 3, 4 … */
export function zigzag(value: number): number {
  return value >= 0 ? value * 2 : -value * 2 - 1;
}

/** Inverse of zigzag. */
export function unzigzag(value: number): number {
  return value % 2 === 0 ? value / 2 : -(value + 1) / 2;
}

/** Bits an Exp-Golomb code of order k takes for `value`. */
export function expGolombBits(value: number, k: number): number {
  const high = Math.floor(value / ((1 << k) >>> 0));
  const m = 31 - Math.clz32(high + 1);
  return 2 * m + 1 + k;
}

/** The Exp-Golomb order (0..maxK) that codes all `values` in the fewest bits. */
export function bestExpGolombOrder(values: ArrayLike<number>, count: number, maxK = 15): number {
  if (count === 0) return 0;
  let bestK = 0;
  let bestBits = Infinity;
  for (let k = 0; k <= maxK; k++) {
    // expGolombBits per value, with the division as a shift (codable values are below 2^31).
    let bits = 0;
    for (let i = 0; i < count; i++) bits += 2 * (31 - Math.clz32((values[i] >>> k) + 1)) + 1 + k;
    if (bits < bestBits) {
      bestBits = bits;
      bestK = k;
    }
  }
  return bestK;
}

/** Bits needed to store every integer in 0..maxValue. */
export function bitsFor(maxValue: number): number {
  return maxValue <= 0 ? 0 : 32 - Math.clz32(maxValue);
}
