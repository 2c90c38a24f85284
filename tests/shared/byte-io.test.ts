// Tests of shared/byte-io.ts: every value round-trips bit for bit in little-endian order, varints take the fewest
// bytes, and a short or malformed read throws a PayloadError that names the field (and the reader's context).
import { describe, expect, it } from 'vitest';
import { ByteReader, ByteWriter, MAX_VARINT, PayloadError } from '../../shared/byte-io.ts';

describe('ByteWriter / ByteReader', () => {
  it('round-trips every kind of value in order, through buffer growth', () => {
    const w = new ByteWriter(4);
    w.u8(255).i8(-128).u16(65535).i16(-32768).u32(0xfedcba98).i32(-2).f64(-0).f64(Math.PI);
    w.uvarint(0).uvarint(300).uvarint(MAX_VARINT).raw(Uint8Array.of(9, 8)).u32PrefixedBytes(Uint8Array.of(7));
    w.u32PrefixedString('héllo').varintPrefixedString('✓ ok').f64s([1.5, Number.NaN]).u32s([1, 0xffffffff]);
    const bytes = w.finish();
    expect(w.capacityBytes).toBeGreaterThanOrEqual(bytes.length);
    const r = new ByteReader(bytes);
    expect([r.u8(), r.i8(), r.u16(), r.i16(), r.u32(), r.i32()]).toEqual([255, -128, 65535, -32768, 0xfedcba98, -2]);
    expect(Object.is(r.f64(), -0)).toBe(true);
    expect(r.f64()).toBe(Math.PI);
    expect([r.uvarint(), r.uvarint(), r.uvarint()]).toEqual([0, 300, MAX_VARINT]);
    expect([...r.raw(2)]).toEqual([9, 8]);
    expect([...r.u32PrefixedBytes('blob')]).toEqual([7]);
    expect(r.u32PrefixedString('name')).toBe('héllo');
    expect(r.varintPrefixedString(16, 'label')).toBe('✓ ok');
    expect(r.f64s('values')).toEqual([1.5, Number.NaN]);
    expect(r.u32s('ids')).toEqual([1, 0xffffffff]);
    expect(r.remaining).toBe(0);
    r.expectEnd('sample');
  });

  it('writes little-endian fixed widths and LEB128 varints of the fewest bytes', () => {
    const w = new ByteWriter().u32(0x01020304).uvarint(127).uvarint(128).uvarint(2 ** 31);
    expect([...w.view()]).toEqual([4, 3, 2, 1, 0x7f, 0x80, 0x01, 0x80, 0x80, 0x80, 0x80, 0x08]);
    expect(() => w.uvarint(-1)).toThrow(RangeError);
    w.patchU32(0, 7);
    expect([...w.view().subarray(0, 4)]).toEqual([7, 0, 0, 0]);
    w.reset();
    expect(w.length).toBe(0);
  });

  it('reads only its window and names the field and context of a short read', () => {
    const bytes = Uint8Array.of(1, 2, 3, 4, 5, 6);
    const r = new ByteReader(bytes, 1, 4, 'checkpoint');
    expect(r.u16('a')).toBe(2 | (3 << 8));
    expect(r.offset).toBe(3);
    expect(() => r.u32('player id')).toThrow(/^checkpoint ends inside player id at byte 3 \(needs 4 byte\(s\), 1 left\)$/);
    expect(() => new ByteReader(bytes).f64('x')).toThrow(/^payload ends inside x/);
  });

  it('refuses malformed lengths, counts, varints, UTF-8 and trailing bytes with a PayloadError', () => {
    const check = (bytes: number[], read: (r: ByteReader) => unknown, message: RegExp): void => {
      const attempt = (): unknown => read(new ByteReader(Uint8Array.from(bytes), 0, bytes.length, 'rec'));
      expect(attempt).toThrow(PayloadError);
      expect(attempt).toThrow(message);
    };
    check([5, 0, 0, 0, 1], (r) => r.u32PrefixedBytes('blob'), /rec ends inside blob/);
    check([200, 0, 0, 0], (r) => r.count('items', 4), /^rec: items 200 exceeds the bytes left \(0\)$/);
    check([0x80, 0x80, 0x80, 0x80, 0x80, 0x80, 0x80, 0x80, 0x01], (r) => r.uvarint('tick'), /^rec: tick is longer than 8 bytes$/);
    check([0xff, 0xff, 0xff, 0xff, 0xff, 0xff, 0xff, 0x10], (r) => r.uvarint('tick'), /^rec: tick \d+ exceeds 2\^53 - 1$/);
    check([2, 0xc3, 0x28], (r) => r.varintPrefixedString(10, 'name'), /^rec: name is not valid UTF-8$/);
    check([11], (r) => r.varintPrefixedString(10, 'name'), /^rec: name is 11 bytes \(limit 10\)$/);
    check([0, 0, 0, 0, 0, 0, 0xf0, 0x7f], (r) => r.finite('x'), /^rec: x is not finite$/);
    check([1, 2], (r) => (r.u8(), r.expectEnd('header')), /^rec: 1 unexpected trailing byte\(s\) in header$/);
  });
});
