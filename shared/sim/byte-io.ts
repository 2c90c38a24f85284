// Little-endian binary writer and bounds-checked reader for the checkpoint byte form. Every read past the end or of
// an impossible length throws a clear Error naming the field, so corrupt input never reaches Jolt.

const encoder = new TextEncoder();
const decoder = new TextDecoder('utf-8', { fatal: true });

/** A growable little-endian byte writer. */
export class ByteWriter {
  private buf = new Uint8Array(4096);
  private view = new DataView(this.buf.buffer);
  private pos = 0;

  private room(n: number): void {
    if (this.pos + n <= this.buf.length) return;
    let cap = this.buf.length * 2;
    while (cap < this.pos + n) cap *= 2;
    const next = new Uint8Array(cap);
    next.set(this.buf.subarray(0, this.pos));
    this.buf = next;
    this.view = new DataView(next.buffer);
  }

  get length(): number {
    return this.pos;
  }

  u8(v: number): this {
    this.room(1);
    this.view.setUint8(this.pos, v);
    this.pos += 1;
    return this;
  }

  u32(v: number): this {
    this.room(4);
    this.view.setUint32(this.pos, v >>> 0, true);
    this.pos += 4;
    return this;
  }

  i32(v: number): this {
    this.room(4);
    this.view.setInt32(this.pos, v | 0, true);
    this.pos += 4;
    return this;
  }

  f64(v: number): this {
    this.room(8);
    this.view.setFloat64(this.pos, v, true);
    this.pos += 8;
    return this;
  }

  /** Raw bytes, no length. */
  raw(bytes: Uint8Array): this {
    this.room(bytes.length);
    this.buf.set(bytes, this.pos);
    this.pos += bytes.length;
    return this;
  }

  /** Length-prefixed bytes. */
  bytes(bytes: Uint8Array): this {
    return this.u32(bytes.length).raw(bytes);
  }

  /** Length-prefixed UTF-8. */
  string(s: string): this {
    return this.bytes(encoder.encode(s));
  }

  /** Length-prefixed float64 array. */
  f64s(values: ArrayLike<number>): this {
    this.u32(values.length);
    this.room(values.length * 8);
    for (let i = 0; i < values.length; i++) {
      this.view.setFloat64(this.pos, values[i], true);
      this.pos += 8;
    }
    return this;
  }

  /** Length-prefixed uint32 array. */
  u32s(values: ArrayLike<number>): this {
    this.u32(values.length);
    for (let i = 0; i < values.length; i++) this.u32(values[i]);
    return this;
  }

  /** Overwrites a uint32 written earlier (section lengths). */
  patchU32(at: number, v: number): void {
    this.view.setUint32(at, v >>> 0, true);
  }

  /** A copy of what was written. */
  finish(): Uint8Array {
    return this.buf.slice(0, this.pos);
  }
}

/** A bounds-checked little-endian reader. */
export class ByteReader {
  readonly bytes: Uint8Array;
  private readonly view: DataView;
  private pos: number;
  private readonly end: number;
  private readonly what: string;

  constructor(bytes: Uint8Array, what: string, start = 0, end = bytes.length) {
    this.bytes = bytes;
    this.view = new DataView(bytes.buffer, bytes.byteOffset, bytes.byteLength);
    this.pos = start;
    this.end = end;
    this.what = what;
  }

  get offset(): number {
    return this.pos;
  }

  get remaining(): number {
    return this.end - this.pos;
  }

  private need(n: number, field: string): void {
    if (n < 0 || this.pos + n > this.end) throw new Error(`${this.what}: truncated or corrupt at byte ${this.pos} (reading ${field})`);
  }

  u8(field: string): number {
    this.need(1, field);
    return this.view.getUint8(this.pos++);
  }

  u32(field: string): number {
    this.need(4, field);
    const v = this.view.getUint32(this.pos, true);
    this.pos += 4;
    return v;
  }

  i32(field: string): number {
    this.need(4, field);
    const v = this.view.getInt32(this.pos, true);
    this.pos += 4;
    return v;
  }

  f64(field: string): number {
    this.need(8, field);
    const v = this.view.getFloat64(this.pos, true);
    this.pos += 8;
    return v;
  }

  /** A finite float64. */
  finite(field: string): number {
    const v = this.f64(field);
    if (!Number.isFinite(v)) throw new Error(`${this.what}: ${field} is not finite`);
    return v;
  }

  raw(n: number, field: string): Uint8Array {
    this.need(n, field);
    const out = this.bytes.subarray(this.pos, this.pos + n);
    this.pos += n;
    return out;
  }

  bytesField(field: string): Uint8Array {
    return this.raw(this.u32(`${field} length`), field).slice();
  }

  string(field: string): string {
    const raw = this.raw(this.u32(`${field} length`), field);
    try {
      return decoder.decode(raw);
    } catch {
      throw new Error(`${this.what}: ${field} is not valid UTF-8`);
    }
  }

  /** A count, checked against the bytes left given the smallest size of one item. */
  count(field: string, minItemBytes: number): number {
    const n = this.u32(field);
    if (n * minItemBytes > this.remaining) throw new Error(`${this.what}: ${field} ${n} exceeds the bytes left (${this.remaining})`);
    return n;
  }

  f64s(field: string): number[] {
    const n = this.count(`${field} count`, 8);
    const out = new Array<number>(n);
    for (let i = 0; i < n; i++) out[i] = this.f64(field);
    return out;
  }

  u32s(field: string): number[] {
    const n = this.count(`${field} count`, 4);
    const out = new Array<number>(n);
    for (let i = 0; i < n; i++) out[i] = this.u32(field);
    return out;
  }
}
