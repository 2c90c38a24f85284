// A msgpack byte writer for hostile tests: every encoding chosen by hand (−0 as a float, small numbers as 64-bit
// integers, lying lengths, extension types, reserved bytes), which a real encoder would never produce.

/** Integer encodings; `fix` is a positive or negative fixint. */
export type IntWidth = 'fix' | 'u8' | 'u16' | 'u32' | 'u64' | 'i8' | 'i16' | 'i32' | 'i64';

const textEncoder = new TextEncoder();
const utf8Cache = new Map<string, Uint8Array>();
const scratchBytes = new Uint8Array(8);
const scratch = new DataView(scratchBytes.buffer);

/** Appends msgpack tokens to a growing byte list. */
export class MsgpackWriter {
  private readonly out: number[] = [];

  /** Raw bytes, as given. */
  raw(...bytes: number[]): this {
    for (const b of bytes) this.out.push(b & 0xff);
    return this;
  }

  /** Raw bytes from an array (no argument spreading: any length). */
  rawBytes(bytes: ArrayLike<number>): this {
    for (let i = 0; i < bytes.length; i++) this.out.push(bytes[i] & 0xff);
    return this;
  }

  private be(value: number | bigint, bytes: number): this {
    if (typeof value === 'number' && bytes <= 4 && Number.isInteger(value)) {
      for (let i = bytes - 1; i >= 0; i--) this.out.push(Math.floor(value / 2 ** (8 * i)) & 0xff);
      return this;
    }
    let v = BigInt.asUintN(bytes * 8, BigInt(value));
    const at = this.out.length;
    for (let i = 0; i < bytes; i++) {
      this.out.splice(at, 0, Number(v & 0xffn));
      v >>= 8n;
    }
    return this;
  }

  nil(): this {
    return this.raw(0xc0);
  }

  bool(value: boolean): this {
    return this.raw(value ? 0xc3 : 0xc2);
  }

  /** An integer in the given width (the caller keeps it in range; extra bits are cut like a C cast). */
  int(value: number | bigint, width: IntWidth): this {
    switch (width) {
      case 'fix':
        return this.raw(Number(BigInt.asUintN(8, BigInt(value))));
      case 'u8':
        return this.raw(0xcc).be(value, 1);
      case 'u16':
        return this.raw(0xcd).be(value, 2);
      case 'u32':
        return this.raw(0xce).be(value, 4);
      case 'u64':
        return this.raw(0xcf).be(value, 8);
      case 'i8':
        return this.raw(0xd0).be(value, 1);
      case 'i16':
        return this.raw(0xd1).be(value, 2);
      case 'i32':
        return this.raw(0xd2).be(value, 4);
      case 'i64':
        return this.raw(0xd3).be(value, 8);
    }
  }

  f32(value: number): this {
    scratch.setFloat32(0, value);
    return this.raw(0xca).rawBytes(scratchBytes.subarray(0, 4));
  }

  f64(value: number): this {
    scratch.setFloat64(0, value);
    return this.raw(0xcb).rawBytes(scratchBytes);
  }

  /** A string header claiming `length` bytes (fixstr when it fits and `wide` is not set). */
  strHeader(length: number, wide = false): this {
    if (length < 32 && !wide) return this.raw(0xa0 | length);
    if (length < 256) return this.raw(0xd9, length);
    if (length < 65536) return this.raw(0xda).be(length, 2);
    return this.raw(0xdb).be(length, 4);
  }

  str(text: string, wide = false): this {
    let b = utf8Cache.get(text);
    if (b === undefined) {
      b = textEncoder.encode(text);
      if (text.length <= 32 && utf8Cache.size < 4096) utf8Cache.set(text, b);
    }
    return this.strHeader(b.length, wide).rawBytes(b);
  }

  bin(bytes: Uint8Array): this {
    if (bytes.length < 256) this.raw(0xc4, bytes.length);
    else if (bytes.length < 65536) this.raw(0xc5).be(bytes.length, 2);
    else this.raw(0xc6).be(bytes.length, 4);
    return this.rawBytes(bytes);
  }

  /** An array header of `count` values (may lie about what follows). */
  arrayHeader(count: number, wide = false): this {
    if (count < 16 && !wide) return this.raw(0x90 | count);
    if (count < 65536) return this.raw(0xdc).be(count, 2);
    return this.raw(0xdd).be(count, 4);
  }

  /** A map header of `count` key/value pairs (may lie about what follows). */
  mapHeader(count: number, wide = false): this {
    if (count < 16 && !wide) return this.raw(0x80 | count);
    if (count < 65536) return this.raw(0xde).be(count, 2);
    return this.raw(0xdf).be(count, 4);
  }

  /** An extension value of `type` with `data` (fixext when the size allows). */
  ext(type: number, data: Uint8Array): this {
    const fixed: Record<number, number> = { 1: 0xd4, 2: 0xd5, 4: 0xd6, 8: 0xd7, 16: 0xd8 };
    if (fixed[data.length] !== undefined) return this.raw(fixed[data.length], type).rawBytes(data);
    if (data.length < 256) return this.raw(0xc7, data.length, type).rawBytes(data);
    return this.raw(0xc8).be(data.length, 2).raw(type).rawBytes(data);
  }

  get length(): number {
    return this.out.length;
  }

  finish(): Uint8Array {
    return Uint8Array.from(this.out);
  }
}
