// Tests of the input frame fast path: every frame it reads gives exactly the fields msgpack decoding gives (so the
// validator sees the same thing either way), the frames clients send take it, and anything else is left to the
// general decoder.
import { describe, expect, it } from 'vitest';
import { decodeFrame, encodeClientMessage } from '../../../shared/protocol/codec.ts';
import { readInputFrame } from '../../../shared/protocol/input-frame-reader.ts';
import { MAX_CLIENT_FRAME_DEPTH } from '../../../shared/protocol/limits.ts';
import { ClientOpcode } from '../../../shared/protocol/opcodes.ts';
import { decodeClientMessage } from '../../../shared/protocol/validation.ts';
import { Prng } from '../../../shared/sim/prng.ts';
import { EDGE_NUMBERS, frameHex, hostileFrame, writeNumber } from '../../helpers/hostile-frames.ts';
import { MsgpackWriter, type IntWidth } from '../../helpers/msgpack-writer.ts';

/** What the general path decodes `bytes` to, or undefined when it refuses them. */
function general(bytes: Uint8Array): unknown {
  const r = decodeFrame(bytes, MAX_CLIENT_FRAME_DEPTH);
  return r.ok ? r.value : undefined;
}

/** The msgpack int encodings that hold `n`. */
function widthsFor(n: number): IntWidth[] {
  const widths: IntWidth[] = ['i64'];
  if (n >= -32 && n <= 127) widths.push('fix');
  if (n >= 0) widths.push(...(['u8', 'u16', 'u32', 'u64'] as const).filter((_, i) => i === 3 || n < 2 ** (8 << i)));
  if (n >= -128 && n <= 127) widths.push('i8');
  if (n >= -32768 && n <= 32767) widths.push('i16');
  if (n >= -(2 ** 31) && n < 2 ** 31) widths.push('i32');
  return widths;
}

const walk = { moveX: -90, moveZ: 127, yaw: 40_123, pitch: -1200, buttons: 4 };

/** An input-shaped frame with random widths, values, lengths and flaws (floats, game values, wrong sizes, trailers). */
function inputLike(rng: Prng): Uint8Array {
  const w = new MsgpackWriter();
  const withAck = rng.next() < 0.5;
  w.arrayHeader(withAck ? 4 : 3, rng.next() < 0.03);
  if (rng.next() < 0.97) w.raw(ClientOpcode.Input);
  else writeNumber(w, rng, rng.pick([1, 3, 2.5, -2]));
  // Most frames hold integers only (each in a random width that fits it), the rest any number in any encoding.
  const clean = rng.next() < 0.7;
  const wide = rng.next() < 0.1; // 64-bit widths too (which the fast path leaves alone)
  const number = (): void => {
    const n = rng.next() < 0.95 ? rng.int(-70_000, 70_000) : rng.pick(EDGE_NUMBERS);
    if (clean && Number.isSafeInteger(n) && !Object.is(n, -0)) w.int(n, rng.pick(widthsFor(n).filter((width) => wide || !width.endsWith('64'))));
    else writeNumber(w, rng, n);
  };
  number();
  const count = rng.next() < 0.8 ? rng.int(1, 4) : rng.int(0, 17);
  w.arrayHeader(count, rng.next() < 0.03);
  for (let i = 0; i < count; i++) {
    const fields = rng.next() < 0.98 ? 5 : rng.pick([4, 6]);
    w.arrayHeader(fields);
    for (let f = 0; f < Math.min(fields, 5); f++) number();
    if (fields === 6) w.arrayHeader(1).int(3, 'fix');
  }
  if (withAck) number();
  if (rng.next() < 0.05) w.raw(0x00);
  const bytes = w.finish();
  return rng.next() < 0.05 ? bytes.subarray(0, rng.int(0, bytes.length - 1)) : bytes;
}

describe('input-frame-reader', () => {
  it('reads the input frames the client library sends, as msgpack decoding does', () => {
    for (const commands of [[walk], [walk, walk, { ...walk, buttons: 5 }, walk], Array.from({ length: 15 }, (_, i) => ({ ...walk, yaw: i * 4000 }))]) {
      for (const message of [
        { type: 'input', firstTick: 123_456, commands } as const,
        { type: 'input', firstTick: 7, commands, ackTick: 5 } as const,
        { type: 'input', firstTick: 4_000_000_000, commands, ackTick: 3_999_999_990 } as const,
      ]) {
        const bytes = encodeClientMessage(message);
        const fields = readInputFrame(bytes);
        expect(fields).not.toBeNull();
        expect(fields).toEqual(general(bytes));
        expect(decodeClientMessage(bytes)).toEqual({ ok: true, message, clampedCommands: 0 });
      }
    }
  });

  it('reads every int width msgpack has up to 32 bits, signed and unsigned', () => {
    const w = new MsgpackWriter().arrayHeader(3).raw(ClientOpcode.Input).int(0xffff_ffff, 'u32').arrayHeader(2);
    w.arrayHeader(5).int(-32, 'fix').int(200, 'u8').int(-100, 'i8').int(-30_000, 'i16').int(60_000, 'u16');
    w.arrayHeader(5).int(-(2 ** 31), 'i32').int(2 ** 31 - 1, 'i32').int(5, 'u16').int(127, 'fix').int(0, 'u32');
    const bytes = w.finish();
    expect(readInputFrame(bytes)).toEqual([ClientOpcode.Input, 0xffff_ffff, [[-32, 200, -100, -30_000, 60_000], [-(2 ** 31), 2 ** 31 - 1, 5, 127, 0]]]);
    expect(readInputFrame(bytes)).toEqual(general(bytes));
  });

  it('leaves floats, game values, 64-bit ints, other opcodes, wrong lengths and trailing bytes to the general path', () => {
    const frame = (build: (w: MsgpackWriter) => void): Uint8Array => {
      const w = new MsgpackWriter();
      build(w);
      return w.finish();
    };
    const five = (w: MsgpackWriter): MsgpackWriter => w.arrayHeader(5).raw(1, 2, 3, 4, 5);
    const refused = [
      frame((w) => five(w.arrayHeader(3).raw(ClientOpcode.Input, 9).arrayHeader(1).arrayHeader(5).f64(1.5).raw(2, 3, 4, 5))),
      frame((w) => w.arrayHeader(3).raw(ClientOpcode.Input, 9).arrayHeader(1).arrayHeader(6).raw(1, 2, 3, 4, 5).arrayHeader(1).raw(1)),
      frame((w) => five(w.arrayHeader(3).raw(ClientOpcode.Input).int(9, 'u64').arrayHeader(1))),
      frame((w) => five(w.arrayHeader(3).raw(ClientOpcode.Hello, 9).arrayHeader(1))),
      frame((w) => five(w.arrayHeader(3).raw(ClientOpcode.Input, 9).arrayHeader(1)).raw(0)),
      frame((w) => five(w.arrayHeader(4).raw(ClientOpcode.Input, 9).arrayHeader(1))),
      frame((w) => w.arrayHeader(3).raw(ClientOpcode.Input, 9).arrayHeader(0)),
      frame((w) => w.arrayHeader(3).raw(ClientOpcode.Input, 9).arrayHeader(16, true)),
      frame((w) => five(w.arrayHeader(3).raw(ClientOpcode.Input, 9).arrayHeader(1)).raw(0)).subarray(0, 8),
    ];
    for (const bytes of refused) expect(readInputFrame(bytes), frameHex({ kind: 'edge-message', data: bytes })).toBeNull();
  });

  it('agrees with msgpack decoding on every generated input-like and hostile frame it reads', () => {
    const rng = new Prng(21);
    let read = 0;
    for (let i = 0; i < 20_000; i++) {
      const data = i % 2 === 0 ? inputLike(rng) : hostileFrame(rng, i).data;
      if (typeof data === 'string') continue;
      const fields = readInputFrame(data);
      if (fields === null) continue;
      read++;
      expect(fields, frameHex({ kind: 'mutated', data })).toEqual(general(data));
    }
    // The property says something only when the fast path takes many of them.
    expect(read).toBeGreaterThan(1000);
  });
});
