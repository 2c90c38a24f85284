// Little-endian byte writer/reader for input-log payloads: unsigned LEB128 varints, fixed-width ints, f64, UTF-8
// strings. The reader is bounds-checked and throws PayloadError; neither touches files (pure, portable).

const encoder = new TextEncoder();
const decoder = new TextDecoder('utf-8', { fatal: true });

/** Largest value a varint may carry (2^53 - 1: exact as a JS number). */
export const MAX_VARINT = Number.MAX_SAFE_INTEGER;
/** Longest varint encoding accepted (8 × 7 = 56 bits ≥ 53). */
export const MAX_VARINT_BYTES = 8;

/** A malformed payload: the bytes do not decode as the record type says (reported as corruption). */
export class PayloadError extends Error {
  override name = 'PayloadError';
}

/** Appends values to a growable byte buffer. */
export class ByteWriter {
  private buf: Uint8Array;
  private dv: DataView;
  /** Bytes written so far. */
  length = 0;

  constructor(initialSizeBytes = 256) {
    this.buf = new Uint8Array(initialSizeBytes);
    this.dv = new DataView(this.buf.buffer);
  }

  private reserve(n: number): void {
    if (this.length + n <= this.buf.length) return;
    const grown = new Uint8Array(Math.max(this.buf.length * 2, this.length + n));
    grown.set(this.buf.subarray(0, this.length));
    this.buf = grown;
    this.dv = new DataView(grown.buffer);
  }

  /** One unsigned byte. */
  u8(value: number): void {
    this.reserve(1);
    this.buf[this.length++] = value & 0xff;
  }

  /** Signed 8-bit. */
  i8(value: number): void {
    this.reserve(1);
    this.dv.setInt8(this.length, value);
    this.length += 1;
  }

  /** Unsigned 16-bit little-endian. */
  u16(value: number): void {
    this.reserve(2);
    this.dv.setUint16(this.length, value, true);
    this.length += 2;
  }

  /** Signed 16-bit little-endian. */
  i16(value: number): void {
    this.reserve(2);
    this.dv.setInt16(this.length, value, true);
    this.length += 2;
  }

  /** Unsigned 32-bit little-endian. */
  u32(value: number): void {
    this.reserve(4);
    this.dv.setUint32(this.length, value >>> 0, true);
    this.length += 4;
  }

  /** IEEE-754 double, little-endian (exact bits). */
  f64(value: number): void {
    this.reserve(8);
    this.dv.setFloat64(this.length, value, true);
    this.length += 8;
  }

  /** Unsigned LEB128 varint of a non-negative safe integer. */
  uvarint(value: number): void {
    if (!Number.isSafeInteger(value) || value < 0) throw new RangeError(`varint must be a non-negative safe integer, got ${value}`);
    this.reserve(MAX_VARINT_BYTES);
    let v = value;
    if (v < 0x80000000) {
      while (v >= 0x80) {
        this.buf[this.length++] = (v & 0x7f) | 0x80;
        v >>>= 7;
      }
      this.buf[this.length++] = v;
      return;
    }
    while (v >= 0x80) {
      this.buf[this.length++] = (v % 0x80) | 0x80;
      v = Math.floor(v / 0x80);
    }
    this.buf[this.length++] = v;
  }

  /** Raw bytes. */
  bytes(src: Uint8Array): void {
    this.reserve(src.length);
    this.buf.set(src, this.length);
    this.length += src.length;
  }

  /** UTF-8 string prefixed by its byte length (varint). */
  string(text: string): void {
    const b = encoder.encode(text);
    this.uvarint(b.length);
    this.bytes(b);
  }

  /** The bytes written so far (a view into the internal buffer: valid until the next write or reset). */
  view(): Uint8Array {
    return this.buf.subarray(0, this.length);
  }

  /** Forgets the bytes written (keeps the buffer, so a reused writer allocates nothing). */
  reset(): void {
    this.length = 0;
  }

  /** Buffer capacity in bytes. */
  get capacityBytes(): number {
    return this.buf.length;
  }

  /** A copy of the bytes written. */
  finish(): Uint8Array {
    return this.buf.slice(0, this.length);
  }
}

/** Reads values from bytes[start, end); every read past `end` throws PayloadError. Allocates nothing per read. */
export class ByteReader {
  private readonly buf: Uint8Array;
  private readonly end: number;
  private dv: DataView | null = null;
  /** Next byte to read. */
  pos: number;

  constructor(bytes: Uint8Array, start = 0, end = bytes.length) {
    this.buf = bytes;
    this.pos = start;
    this.end = end;
  }

  /** Bytes left. */
  get remaining(): number {
    return this.end - this.pos;
  }

  private need(n: number, what: string): void {
    if (this.pos + n > this.end) throw new PayloadError(`payload ends inside ${what} (needs ${n} byte(s), ${this.end - this.pos} left)`);
  }

  /** One unsigned byte. */
  u8(what = 'u8'): number {
    this.need(1, what);
    return this.buf[this.pos++];
  }

  /** Signed 8-bit. */
  i8(what = 'i8'): number {
    this.need(1, what);
    return (this.buf[this.pos++] << 24) >> 24;
  }

  /** Unsigned 16-bit little-endian. */
  u16(what = 'u16'): number {
    this.need(2, what);
    const v = this.buf[this.pos] | (this.buf[this.pos + 1] << 8);
    this.pos += 2;
    return v;
  }

  /** Signed 16-bit little-endian. */
  i16(what = 'i16'): number {
    return (this.u16(what) << 16) >> 16;
  }

  /** Unsigned 32-bit little-endian. */
  u32(what = 'u32'): number {
    this.need(4, what);
    const b = this.buf;
    const p = this.pos;
    this.pos += 4;
    return (b[p] | (b[p + 1] << 8) | (b[p + 2] << 16) | (b[p + 3] << 24)) >>> 0;
  }

  /** IEEE-754 double, little-endian. */
  f64(what = 'f64'): number {
    this.need(8, what);
    this.dv ??= new DataView(this.buf.buffer, this.buf.byteOffset, this.buf.byteLength);
    const v = this.dv.getFloat64(this.pos, true);
    this.pos += 8;
    return v;
  }

  /** Unsigned LEB128 varint (at most 8 bytes, value ≤ 2^53 - 1). */
  uvarint(what = 'varint'): number {
    let value = 0;
    let scale = 1;
    for (let i = 0; i < MAX_VARINT_BYTES; i++) {
      this.need(1, what);
      const b = this.buf[this.pos++];
      value += (b & 0x7f) * scale;
      if ((b & 0x80) === 0) {
        if (value > MAX_VARINT) throw new PayloadError(`${what} ${value} exceeds 2^53 - 1`);
        return value;
      }
      scale *= 0x80;
    }
    throw new PayloadError(`${what} is longer than ${MAX_VARINT_BYTES} bytes`);
  }

  /** `n` raw bytes (a view, not a copy). */
  bytes(n: number, what = 'bytes'): Uint8Array {
    this.need(n, what);
    const v = this.buf.subarray(this.pos, this.pos + n);
    this.pos += n;
    return v;
  }

  /** A length-prefixed UTF-8 string of at most `maxBytes` bytes. */
  string(maxBytes: number, what = 'string'): string {
    const n = this.uvarint(`${what} length`);
    if (n > maxBytes) throw new PayloadError(`${what} is ${n} bytes (limit ${maxBytes})`);
    const b = this.bytes(n, what);
    try {
      return decoder.decode(b);
    } catch {
      throw new PayloadError(`${what} is not valid UTF-8`);
    }
  }

  /** Throws unless every byte was consumed. */
  expectEnd(what: string): void {
    if (this.pos !== this.end) throw new PayloadError(`${this.end - this.pos} unexpected trailing byte(s) in ${what}`);
  }
}
