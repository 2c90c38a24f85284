// Little-endian binary writer and bounds-checked reader shared by every byte format (input log records, checkpoints,
// body recipes): fixed-width ints, f64, unsigned LEB128 varints, length-prefixed bytes, strings and arrays. A read
// past the end or of an impossible length throws a PayloadError naming the field, so corrupt input never goes further.

const encoder = new TextEncoder();
const decoder = new TextDecoder('utf-8', { fatal: true });

/** Largest value a varint may carry (2^53 - 1: exact as a JS number). */
export const MAX_VARINT = Number.MAX_SAFE_INTEGER;
/** Longest varint encoding accepted (8 × 7 = 56 bits ≥ 53). */
export const MAX_VARINT_BYTES = 8;

/** Malformed bytes: they do not decode as their format says (readers report it as corruption). */
export class PayloadError extends Error {
  override name = 'PayloadError';
}

/** Appends values to a growable byte buffer. Every method returns the writer, so writes chain. */
export class ByteWriter {
  private buf: Uint8Array;
  private dv: DataView;
  private pos = 0;

  constructor(initialSizeBytes = 256) {
    this.buf = new Uint8Array(initialSizeBytes);
    this.dv = new DataView(this.buf.buffer);
  }

  private reserve(n: number): void {
    if (this.pos + n <= this.buf.length) return;
    const grown = new Uint8Array(Math.max(this.buf.length * 2, this.pos + n));
    grown.set(this.buf.subarray(0, this.pos));
    this.buf = grown;
    this.dv = new DataView(grown.buffer);
  }

  /** Bytes written so far. */
  get length(): number {
    return this.pos;
  }

  /** Buffer capacity in bytes. */
  get capacityBytes(): number {
    return this.buf.length;
  }

  /** One unsigned byte. */
  u8(value: number): this {
    this.reserve(1);
    this.buf[this.pos++] = value & 0xff;
    return this;
  }

  /** Signed 8-bit. */
  i8(value: number): this {
    this.reserve(1);
    this.dv.setInt8(this.pos, value);
    this.pos += 1;
    return this;
  }

  /** Unsigned 16-bit. */
  u16(value: number): this {
    this.reserve(2);
    this.dv.setUint16(this.pos, value, true);
    this.pos += 2;
    return this;
  }

  /** Signed 16-bit. */
  i16(value: number): this {
    this.reserve(2);
    this.dv.setInt16(this.pos, value, true);
    this.pos += 2;
    return this;
  }

  /** Unsigned 32-bit. */
  u32(value: number): this {
    this.reserve(4);
    this.dv.setUint32(this.pos, value >>> 0, true);
    this.pos += 4;
    return this;
  }

  /** Signed 32-bit. */
  i32(value: number): this {
    this.reserve(4);
    this.dv.setInt32(this.pos, value | 0, true);
    this.pos += 4;
    return this;
  }

  /** IEEE-754 double (exact bits). */
  f64(value: number): this {
    this.reserve(8);
    this.dv.setFloat64(this.pos, value, true);
    this.pos += 8;
    return this;
  }

  /** Unsigned LEB128 varint of a non-negative safe integer. */
  uvarint(value: number): this {
    if (!Number.isSafeInteger(value) || value < 0) throw new RangeError(`varint must be a non-negative safe integer, got ${value}`);
    this.reserve(MAX_VARINT_BYTES);
    let v = value;
    if (v < 0x80000000) {
      while (v >= 0x80) {
        this.buf[this.pos++] = (v & 0x7f) | 0x80;
        v >>>= 7;
      }
      this.buf[this.pos++] = v;
      return this;
    }
    while (v >= 0x80) {
      this.buf[this.pos++] = (v % 0x80) | 0x80;
      v = Math.floor(v / 0x80);
    }
    this.buf[this.pos++] = v;
    return this;
  }

  /** Raw bytes, no length. */
  raw(bytes: Uint8Array): this {
    this.reserve(bytes.length);
    this.buf.set(bytes, this.pos);
    this.pos += bytes.length;
    return this;
  }

  /** Bytes prefixed by their length (u32). */
  u32PrefixedBytes(bytes: Uint8Array): this {
    return this.u32(bytes.length).raw(bytes);
  }

  /** UTF-8 prefixed by its byte length (u32). */
  u32PrefixedString(text: string): this {
    return this.u32PrefixedBytes(encoder.encode(text));
  }

  /** UTF-8 prefixed by its byte length (varint). */
  varintPrefixedString(text: string): this {
    const b = encoder.encode(text);
    return this.uvarint(b.length).raw(b);
  }

  /** Float64 array prefixed by its count (u32). */
  f64s(values: ArrayLike<number>): this {
    this.u32(values.length);
    this.reserve(values.length * 8);
    for (let i = 0; i < values.length; i++) {
      this.dv.setFloat64(this.pos, values[i], true);
      this.pos += 8;
    }
    return this;
  }

  /** Uint32 array prefixed by its count (u32). */
  u32s(values: ArrayLike<number>): this {
    this.u32(values.length);
    for (let i = 0; i < values.length; i++) this.u32(values[i]);
    return this;
  }

  /** Overwrites a uint32 written earlier at byte `at` (section lengths). */
  patchU32(at: number, value: number): void {
    this.dv.setUint32(at, value >>> 0, true);
  }

  /** The bytes written so far (a view into the internal buffer: valid until the next write or reset). */
  view(): Uint8Array {
    return this.buf.subarray(0, this.pos);
  }

  /** Forgets the bytes written (keeps the buffer, so a reused writer allocates nothing). */
  reset(): void {
    this.pos = 0;
  }

  /** A copy of the bytes written. */
  finish(): Uint8Array {
    return this.buf.slice(0, this.pos);
  }
}

/**
 * Reads values from bytes[start, end); every read past `end` throws PayloadError. Allocates nothing per fixed-width
 * read. `context` (e.g. "checkpoint") opens every error message; without it short reads speak of the "payload".
 */
export class ByteReader {
  /** The whole buffer this reader reads a window of. */
  readonly bytes: Uint8Array;
  private readonly end: number;
  private readonly context: string | undefined;
  private dv: DataView | null = null;
  private pos: number;

  constructor(bytes: Uint8Array, start = 0, end = bytes.length, context?: string) {
    this.bytes = bytes;
    this.pos = start;
    this.end = end;
    this.context = context;
  }

  /** Next byte to read. */
  get offset(): number {
    return this.pos;
  }

  /** Bytes left. */
  get remaining(): number {
    return this.end - this.pos;
  }

  private fail(message: string): never {
    throw new PayloadError(this.context === undefined ? message : `${this.context}: ${message}`);
  }

  private need(n: number, field: string): void {
    if (n < 0 || this.pos + n > this.end) {
      throw new PayloadError(`${this.context ?? 'payload'} ends inside ${field} at byte ${this.pos} (needs ${n} byte(s), ${this.end - this.pos} left)`);
    }
  }

  private dataView(): DataView {
    this.dv ??= new DataView(this.bytes.buffer, this.bytes.byteOffset, this.bytes.byteLength);
    return this.dv;
  }

  /** One unsigned byte. */
  u8(field = 'u8'): number {
    this.need(1, field);
    return this.bytes[this.pos++];
  }

  /** Signed 8-bit. */
  i8(field = 'i8'): number {
    this.need(1, field);
    return (this.bytes[this.pos++] << 24) >> 24;
  }

  /** Unsigned 16-bit. */
  u16(field = 'u16'): number {
    this.need(2, field);
    const v = this.bytes[this.pos] | (this.bytes[this.pos + 1] << 8);
    this.pos += 2;
    return v;
  }

  /** Signed 16-bit. */
  i16(field = 'i16'): number {
    return (this.u16(field) << 16) >> 16;
  }

  /** Unsigned 32-bit. */
  u32(field = 'u32'): number {
    this.need(4, field);
    const b = this.bytes;
    const p = this.pos;
    this.pos += 4;
    return (b[p] | (b[p + 1] << 8) | (b[p + 2] << 16) | (b[p + 3] << 24)) >>> 0;
  }

  /** Signed 32-bit. */
  i32(field = 'i32'): number {
    return this.u32(field) | 0;
  }

  /** IEEE-754 double. */
  f64(field = 'f64'): number {
    this.need(8, field);
    const v = this.dataView().getFloat64(this.pos, true);
    this.pos += 8;
    return v;
  }

  /** A finite double. */
  finite(field: string): number {
    const v = this.f64(field);
    if (!Number.isFinite(v)) this.fail(`${field} is not finite`);
    return v;
  }

  /** Unsigned LEB128 varint (at most 8 bytes, value ≤ 2^53 - 1). */
  uvarint(field = 'varint'): number {
    let value = 0;
    let scale = 1;
    for (let i = 0; i < MAX_VARINT_BYTES; i++) {
      this.need(1, field);
      const b = this.bytes[this.pos++];
      value += (b & 0x7f) * scale;
      if ((b & 0x80) === 0) {
        if (value > MAX_VARINT) this.fail(`${field} ${value} exceeds 2^53 - 1`);
        return value;
      }
      scale *= 0x80;
    }
    return this.fail(`${field} is longer than ${MAX_VARINT_BYTES} bytes`);
  }

  /** `n` raw bytes (a view, not a copy). */
  raw(n: number, field = 'bytes'): Uint8Array {
    this.need(n, field);
    const v = this.bytes.subarray(this.pos, this.pos + n);
    this.pos += n;
    return v;
  }

  /** Bytes prefixed by their length (u32), copied out. */
  u32PrefixedBytes(field: string): Uint8Array {
    return this.raw(this.u32(`${field} length`), field).slice();
  }

  /** UTF-8 prefixed by its byte length (u32). */
  u32PrefixedString(field: string): string {
    return this.utf8(this.raw(this.u32(`${field} length`), field), field);
  }

  /** UTF-8 prefixed by its byte length (varint), at most `maxBytes` bytes. */
  varintPrefixedString(maxBytes: number, field = 'string'): string {
    const n = this.uvarint(`${field} length`);
    if (n > maxBytes) this.fail(`${field} is ${n} bytes (limit ${maxBytes})`);
    return this.utf8(this.raw(n, field), field);
  }

  private utf8(bytes: Uint8Array, field: string): string {
    try {
      return decoder.decode(bytes);
    } catch {
      return this.fail(`${field} is not valid UTF-8`);
    }
  }

  /** A u32 count, checked against the bytes left given the smallest size of one item. */
  count(field: string, minItemBytes: number): number {
    const n = this.u32(field);
    if (n * minItemBytes > this.remaining) this.fail(`${field} ${n} exceeds the bytes left (${this.remaining})`);
    return n;
  }

  /** Float64 array prefixed by its count (u32). */
  f64s(field: string): number[] {
    const n = this.count(`${field} count`, 8);
    const out = new Array<number>(n);
    for (let i = 0; i < n; i++) out[i] = this.f64(field);
    return out;
  }

  /** Uint32 array prefixed by its count (u32). */
  u32s(field: string): number[] {
    const n = this.count(`${field} count`, 4);
    const out = new Array<number>(n);
    for (let i = 0; i < n; i++) out[i] = this.u32(field);
    return out;
  }

  /** Throws unless every byte was consumed. */
  expectEnd(what: string): void {
    if (this.pos !== this.end) this.fail(`${this.end - this.pos} unexpected trailing byte(s) in ${what}`);
  }
}
