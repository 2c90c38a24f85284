// Tests of scanMsgpack (and unpackFrame, which runs it first): plain msgpack passes, every extension type, reserved
// byte, non-string or __proto__ key, over-deep nesting, lying length, truncation and trailing byte is refused with
// its byte offset, and whatever passes decodes to plain values only.
import { describe, expect, it } from 'vitest';
import { FrameError, packValue, unpackFrame } from '../../../shared/protocol/codec.ts';
import { scanMsgpack } from '../../../shared/protocol/msgpack-scan.ts';
import { Prng } from '../../../shared/sim/prng.ts';
import { hostileFrame } from '../../helpers/hostile-frames.ts';
import { MsgpackWriter } from '../../helpers/msgpack-writer.ts';

const bytes = (...b: number[]): Uint8Array => Uint8Array.from(b);

/** Why a decoded value is not plain data (null, boolean, number, string, bytes, array, plain object), or null. */
function notPlain(v: unknown, depth = 0): string | null {
  if (depth > 64) return 'too deep';
  if (v === null || typeof v === 'boolean' || typeof v === 'number' || typeof v === 'string' || v instanceof Uint8Array) return null;
  if (Array.isArray(v)) {
    for (const x of v) {
      const why = notPlain(x, depth + 1);
      if (why) return why;
    }
    return null;
  }
  if (typeof v === 'object' && Object.getPrototypeOf(v) === Object.prototype) {
    for (const [k, x] of Object.entries(v)) {
      if (k === '__proto__') return 'a __proto__ key';
      const why = notPlain(x, depth + 1);
      if (why) return why;
    }
    return null;
  }
  return `a ${typeof v} (${Object.prototype.toString.call(v)})`;
}

describe('scanMsgpack', () => {
  it('passes every plain value the codec writes', () => {
    const plain = [null, true, false, 0, -1, -33, 255, 65536, 2 ** 32, -(2 ** 40), 1.5, -0, Number.NaN, 'x'.repeat(40), 'é', new Uint8Array(300), [], [1, [2, [3]]], { a: 1, toString: 2, valueOf: [] }];
    for (const v of plain) expect(scanMsgpack(packValue(v), 8), JSON.stringify(v)).toBeNull();
  });

  it('refuses extension types and the reserved byte, and decodes 64-bit integers as numbers', () => {
    expect(scanMsgpack(new MsgpackWriter().arrayHeader(2).int(1, 'fix').ext(0x72, bytes(0x40)).finish(), 8)).toBe('byte 2: msgpack extension types are not accepted');
    expect(scanMsgpack(new MsgpackWriter().ext(0x42, bytes(5)).finish(), 8)).toMatch(/extension/);
    expect(scanMsgpack(bytes(0x91, 0xc1), 8)).toBe('byte 1: 0xc1 is not a msgpack type');
    expect(scanMsgpack(new MsgpackWriter().int(2n ** 64n - 1n, 'u64').finish(), 8)).toBeNull();
    expect(unpackFrame(new MsgpackWriter().int(5, 'u64').finish())).toBe(5);
    expect(typeof unpackFrame(new MsgpackWriter().int(-(2n ** 63n), 'i64').finish())).toBe('number');
  });

  it('refuses map keys that are not strings, and the key __proto__', () => {
    expect(scanMsgpack(new MsgpackWriter().mapHeader(1).int(1, 'fix').nil().finish(), 8)).toBe('byte 1: a map key must be a string');
    expect(scanMsgpack(new MsgpackWriter().mapHeader(1).str('__proto__').mapHeader(0).finish(), 8)).toBe('byte 1: the map key "__proto__" is not accepted');
    expect(scanMsgpack(new MsgpackWriter().mapHeader(1).str('__proto__', true).nil().finish(), 8)).toMatch(/__proto__/);
    expect(scanMsgpack(new MsgpackWriter().mapHeader(1).str('toString').int(1, 'fix').finish(), 8)).toBeNull();
  });

  it('counts nesting depth and refuses one level past the limit', () => {
    const nested = (levels: number): Uint8Array => {
      const w = new MsgpackWriter();
      for (let i = 0; i < levels; i++) w.arrayHeader(1);
      return w.nil().finish();
    };
    expect(scanMsgpack(nested(8), 8)).toBeNull();
    expect(scanMsgpack(nested(9), 8)).toBe('byte 8: containers nest deeper than 8');
    expect(() => unpackFrame(nested(100_000))).toThrow(FrameError); // no stack overflow: refused before decoding
  });

  it('refuses lengths larger than the frame, truncated values and trailing bytes', () => {
    expect(scanMsgpack(bytes(0xdd, 0xff, 0xff, 0xff, 0xff, 0xc0), 8)).toBe('byte 0: a container of 4294967295 values, but only 1 bytes follow');
    expect(scanMsgpack(bytes(0xdf, 0x7f, 0xff, 0xff, 0xff), 8)).toMatch(/container of 4294967294 values/);
    expect(scanMsgpack(bytes(0xc6, 0xff, 0xff, 0xff, 0xff), 8)).toBe('byte 0: a value of 4294967295 bytes, but only 0 follow');
    expect(scanMsgpack(bytes(0xcb, 0, 0), 8)).toBe('byte 0: a value of 8 bytes, but only 2 follow');
    expect(scanMsgpack(bytes(0x92, 0x01), 8)).toBe('byte 0: a container of 2 values, but only 1 bytes follow');
    expect(scanMsgpack(bytes(0x92, 0x91, 0x01), 8)).toBe('the frame ends at byte 3 inside a value');
    expect(scanMsgpack(bytes(0xda, 0x01), 8)).toBe('the frame ends at byte 2 inside a string length');
    expect(scanMsgpack(bytes(0x01, 0x02), 8)).toBe('1 trailing byte(s) after the value (at byte 1)');
    expect(scanMsgpack(bytes(), 8)).toBe('the frame ends at byte 0 inside a value');
  });

  it('lets only plain values through to the decoder, over 30,000 hostile frames', () => {
    const rng = new Prng(31);
    const problems: string[] = [];
    let passed = 0;
    for (let i = 0; i < 30_000; i++) {
      const frame = hostileFrame(rng, 1000);
      if (typeof frame.data === 'string') continue;
      let value: unknown;
      try {
        value = unpackFrame(frame.data, 16);
      } catch (error) {
        if (!(error instanceof FrameError)) problems.push(`${Buffer.from(frame.data).toString('hex')}: threw ${(error as Error).name}`);
        continue;
      }
      passed++;
      const why = notPlain(value);
      if (why) problems.push(`${Buffer.from(frame.data).toString('hex')}: decoded to ${why}`);
    }
    expect(problems.slice(0, 5)).toEqual([]);
    expect(passed).toBeGreaterThan(5000);
  });
});
