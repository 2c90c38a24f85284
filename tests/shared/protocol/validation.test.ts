// Tests of client message validation: wrong types, shapes, ranges, NaN and Infinity, oversize and garbage frames all
// become precise error results (never exceptions), and input commands go through validateInputCommand. Property
// tests feed generated hostile frames: nothing throws, and every accepted message is canonical.
import { describe, expect, it } from 'vitest';
import type { ClientMessage } from '../../../shared/protocol/client-messages.ts';
import { encodeClientMessage, packValue } from '../../../shared/protocol/codec.ts';
import { MAX_CLIENT_MESSAGE_BYTES, MAX_INPUT_COMMANDS_PER_MESSAGE } from '../../../shared/protocol/limits.ts';
import { ClientOpcode, ErrorCode, PROTOCOL_VERSION } from '../../../shared/protocol/opcodes.ts';
import { checkPlayerName, decodeClientMessage } from '../../../shared/protocol/validation.ts';
import { Prng } from '../../../shared/sim/prng.ts';
import { frameHex, hostileFrame, type FrameKind } from '../../helpers/hostile-frames.ts';
import { MsgpackWriter } from '../../helpers/msgpack-writer.ts';

function errorOf(data: unknown): { code: string; error: string } {
  const r = decodeClientMessage(data);
  if (r.ok) throw new Error(`expected a rejection, got ${JSON.stringify(r.message)}`);
  return { code: r.code, error: r.error };
}

const cmd = [0, 0, 0, 0, 0];

describe('validation', () => {
  it('rejects text, empty, oversize and non-msgpack frames', () => {
    expect(errorOf('{"op":1}').code).toBe(ErrorCode.Malformed);
    expect(errorOf(new Uint8Array(0)).code).toBe(ErrorCode.Malformed);
    expect(errorOf(new Uint8Array(MAX_CLIENT_MESSAGE_BYTES + 1))).toMatchObject({ code: ErrorCode.Oversize, error: expect.stringMatching(/exceeds the 1024-byte limit/) });
    expect(errorOf(new Uint8Array([0xc1]))).toEqual({ code: ErrorCode.Malformed, error: 'not a plain msgpack value: byte 0: 0xc1 is not a msgpack type' });
    expect(errorOf(new Uint8Array([0x92, 0x01])).code).toBe(ErrorCode.Malformed);
    expect(errorOf(new Uint8Array([0x91, 0x05, 0x00])).error).toMatch(/^not a plain msgpack value: 1 trailing byte/);
    expect(errorOf(12).code).toBe(ErrorCode.Malformed);
  });

  it('rejects non-arrays, unknown opcodes and wrong arity with the message name', () => {
    expect(errorOf(packValue({ op: 1 })).error).toMatch(/must be an array/);
    expect(errorOf(packValue([99])).error).toBe('unknown opcode 99');
    expect(errorOf(packValue(['hello'])).error).toBe('unknown opcode "hello"');
    expect(errorOf(packValue([ClientOpcode.Ping])).error).toMatch(/ping must have 1 field/);
    expect(errorOf(packValue([ClientOpcode.Bye, 'extra'])).error).toMatch(/bye must have 0 field/);
  });

  it('checks hello: version, name length and characters, room id', () => {
    expect(errorOf(packValue([ClientOpcode.Hello, '1', 'Ada', null])).error).toMatch(/version/);
    expect(errorOf(packValue([ClientOpcode.Hello, PROTOCOL_VERSION, '   ', null])).error).toMatch(/name must not be empty/);
    expect(errorOf(packValue([ClientOpcode.Hello, PROTOCOL_VERSION, 'x'.repeat(33), null])).error).toMatch(/at most 32/);
    expect(errorOf(packValue([ClientOpcode.Hello, PROTOCOL_VERSION, 'a\u0000b', null])).error).toMatch(/control/);
    expect(errorOf(packValue([ClientOpcode.Hello, PROTOCOL_VERSION, 'evil\u202e', null])).error).toMatch(/direction-override/);
    expect(errorOf(packValue([ClientOpcode.Hello, PROTOCOL_VERSION, 7, null])).error).toBe('hello.name must be a string, got 7');
    expect(errorOf(packValue([ClientOpcode.Hello, PROTOCOL_VERSION, 'Ada', '../etc'])).error).toMatch(/room must be/);
    expect(errorOf(packValue([ClientOpcode.Hello, PROTOCOL_VERSION, 'Ada'])).error).toMatch(/hello must have 3 or 4 fields, got 2/);
    expect(errorOf(packValue([ClientOpcode.Hello, PROTOCOL_VERSION, 'Ada', null, {}, 1])).error).toMatch(/hello must have 3 or 4 fields, got 5/);
    const ok = decodeClientMessage(packValue([ClientOpcode.Hello, PROTOCOL_VERSION, '  Ada Lovelace ', 'r_1']));
    expect(ok).toMatchObject({ ok: true, message: { type: 'hello', name: 'Ada Lovelace', room: 'r_1' } });
    expect(checkPlayerName('Zoë 🚀')).toEqual({ ok: true, name: 'Zoë 🚀' });
  });

  it('reads hello options: seat and resume tokens, each checked, and nothing else', () => {
    const hello = (options: unknown) => packValue([ClientOpcode.Hello, PROTOCOL_VERSION, 'Ada', null, options]);
    expect(decodeClientMessage(hello({ seatToken: 's1.a.b.1.c', resumeToken: 'r-_9' }))).toEqual({
      ok: true,
      message: { type: 'hello', version: PROTOCOL_VERSION, name: 'Ada', room: null, seatToken: 's1.a.b.1.c', resumeToken: 'r-_9' },
      clampedCommands: 0,
    });
    expect(decodeClientMessage(hello(null))).toMatchObject({ ok: true, message: { name: 'Ada' } });
    expect(decodeClientMessage(hello({}))).toMatchObject({ ok: true });
    expect(errorOf(hello({ seat: 'x' })).error).toBe('hello.options has no field "seat" (known: seatToken, resumeToken)');
    expect(errorOf(hello(JSON.parse('{"__proto__": {"resumeToken": "x"}}')))).toEqual({ code: ErrorCode.Malformed, error: 'not a plain msgpack value: byte 11: the map key "__proto__" is not accepted' });
    expect(errorOf(hello(['x'])).error).toMatch(/hello.options must be a map/);
    expect(errorOf(hello(new Uint8Array(3))).error).toMatch(/got binary/);
    expect(errorOf(hello({ resumeToken: 'a b' })).error).toMatch(/hello.options.resumeToken must be 1-256 characters of A-Z a-z 0-9 _ . -, got "a b"/);
    expect(errorOf(hello({ resumeToken: 'x'.repeat(257) })).error).toMatch(/resumeToken must be/);
    expect(errorOf(hello({ seatToken: '' })).error).toMatch(/seatToken must be/);
    expect(errorOf(hello({ seatToken: 5 })).error).toMatch(/seatToken must be .*, got 5$/);
    expect(errorOf(hello({ seatToken: { toString: 1 } })).error).toMatch(/got an object$/);
  });

  it('answers any other protocol version with version-mismatch before reading the rest of the hello', () => {
    const mismatch = (fields: unknown[]) => errorOf(packValue([ClientOpcode.Hello, ...fields]));
    for (const fields of [[1, 'Ada', null], [PROTOCOL_VERSION + 1], [0, { toString: 1 }, 7, 8, 9], [65535, '', '']]) {
      expect(mismatch(fields), JSON.stringify(fields)).toEqual({
        code: ErrorCode.VersionMismatch,
        error: `this server speaks protocol ${PROTOCOL_VERSION} and the client sent protocol ${fields[0] as number}: use a client built for protocol ${PROTOCOL_VERSION}`,
      });
    }
    expect(mismatch([{ toString: 1 }, 'Ada', null])).toEqual({ code: ErrorCode.BadMessage, error: 'hello.version must be an integer in [0, 65535], got an object' });
    expect(mismatch([-1, 'Ada', null]).error).toBe('hello.version must be an integer in [0, 65535], got -1');
    expect(mismatch([]).error).toBe('hello.version must be an integer in [0, 65535], got undefined');
  });

  it('rejects NaN, Infinity, strings and bad shapes in input commands, naming the command and tick', () => {
    const nan = errorOf(packValue([ClientOpcode.Input, 10, [cmd, [Number.NaN, 0, 0, 0, 0]]]));
    expect(nan).toEqual({ code: ErrorCode.BadInput, error: 'input.commands[1] (tick 11): moveX must be finite, got NaN' });
    expect(errorOf(packValue([ClientOpcode.Input, 10, [[0, Infinity, 0, 0, 0]]])).error).toMatch(/moveZ must be finite/);
    expect(errorOf(packValue([ClientOpcode.Input, 10, [[0, 0, '1', 0, 0]]])).error).toMatch(/yaw must be a finite number/);
    expect(errorOf(packValue([ClientOpcode.Input, 10, [[0, 0, 0, 0, -1]]])).error).toMatch(/buttons/);
    expect(errorOf(packValue([ClientOpcode.Input, 10, [[0, 0, 0, 0]]])).error).toMatch(/\[moveX, moveZ, yaw, pitch, buttons\]/);
    expect(errorOf(packValue([ClientOpcode.Input, 10, []])).error).toMatch(/1\.\.16 commands/);
    expect(errorOf(packValue([ClientOpcode.Input, 10, Array(MAX_INPUT_COMMANDS_PER_MESSAGE + 1).fill(cmd)])).code).toBe(ErrorCode.BadInput);
    expect(errorOf(packValue([ClientOpcode.Input, -1, [cmd]])).error).toMatch(/firstTick/);
    expect(errorOf(packValue([ClientOpcode.Input, 1.5, [cmd]])).error).toMatch(/firstTick/);
    expect(errorOf(packValue([ClientOpcode.Input, 0xffff_ffff, [cmd, cmd]])).error).toMatch(/past the largest tick/);
  });

  it('reads a snapshot ack riding on an input message and refuses one that is not a tick', () => {
    const walk = { moveX: 1, moveZ: 2, yaw: 3, pitch: 4, buttons: 1 };
    const carried = decodeClientMessage(encodeClientMessage({ type: 'input', firstTick: 40, commands: [walk], ackTick: 38 }));
    expect(carried).toEqual({ ok: true, clampedCommands: 0, message: { type: 'input', firstTick: 40, commands: [walk], ackTick: 38 } });
    const plain = decodeClientMessage(encodeClientMessage({ type: 'input', firstTick: 40, commands: [walk] }));
    expect(plain.ok && plain.message.type === 'input' && 'ackTick' in plain.message).toBe(false);
    expect(errorOf(packValue([ClientOpcode.Input, 40, [cmd], -1]))).toEqual({ code: ErrorCode.BadMessage, error: 'input.ackTick must be an integer tick in [0, 4294967295], got -1' });
    expect(errorOf(packValue([ClientOpcode.Input, 40, [cmd], 2.5])).error).toMatch(/input.ackTick/);
    expect(errorOf(packValue([ClientOpcode.Input, 40, [cmd], null])).error).toMatch(/input.ackTick/);
    expect(errorOf(packValue([ClientOpcode.Input, 40, [cmd], { valueOf: 3 }])).error).toBe('input.ackTick must be an integer tick in [0, 4294967295], got an object');
    expect(errorOf(packValue([ClientOpcode.Input, 40, [cmd], 38, 1])).error).toBe('input must have 2 or 3 fields, got 4');
  });

  it('clamps out-of-range input values as validateInputCommand does and counts them', () => {
    const r = decodeClientMessage(packValue([ClientOpcode.Input, 3, [[500, -500, 70000, 99999, 0xff]]]));
    expect(r).toEqual({ ok: true, clampedCommands: 1, message: { type: 'input', firstTick: 3, commands: [{ moveX: 127, moveZ: -127, yaw: 70000 - 65536, pitch: 16384, buttons: 15 }] } });
  });

  it('checks ack ticks and ping times', () => {
    expect(errorOf(packValue([ClientOpcode.SnapshotAck, -3])).error).toMatch(/ack.tick/);
    expect(errorOf(packValue([ClientOpcode.SnapshotAck, 2 ** 33])).error).toMatch(/ack.tick/);
    expect(errorOf(packValue([ClientOpcode.Ping, Number.POSITIVE_INFINITY])).error).toMatch(/clientTimeMs/);
    expect(errorOf(packValue([ClientOpcode.Ping, null])).error).toMatch(/clientTimeMs/);
  });

  it('never throws on random garbage and random mutations of valid frames', () => {
    const rng = new Prng(13);
    const valid = encodeClientMessage({ type: 'input', firstTick: 77, commands: [{ moveX: 1, moveZ: 2, yaw: 3, pitch: 4, buttons: 1 }] });
    let accepted = 0;
    for (let i = 0; i < 5000; i++) {
      let bytes: Uint8Array;
      if (i % 2 === 0) {
        bytes = new Uint8Array(rng.int(1, 64));
        for (let k = 0; k < bytes.length; k++) bytes[k] = rng.int(0, 255);
      } else {
        bytes = valid.slice();
        bytes[rng.int(0, bytes.length - 1)] = rng.int(0, 255);
      }
      const r = decodeClientMessage(bytes);
      if (r.ok) accepted++;
      else expect(typeof r.error).toBe('string');
    }
    expect(accepted).toBeLessThan(5000);
  });

  it('answers the frames that once crashed the server (conversion keys where a number belongs) with errors', () => {
    const conversion = (field: (w: MsgpackWriter) => void, head: (w: MsgpackWriter) => void): Uint8Array => {
      const w = new MsgpackWriter();
      head(w);
      field(w);
      return w.finish();
    };
    const toStringMap = (w: MsgpackWriter): void => void w.mapHeader(1).str('toString').int(1, 'fix');
    const valueOfMap = (w: MsgpackWriter): void => void w.mapHeader(2).str('valueOf').int(1, 'fix').str('toString').int(2, 'fix');
    expect(errorOf(conversion(toStringMap, (w) => w.arrayHeader(2).int(ClientOpcode.Ping, 'fix')))).toEqual({ code: ErrorCode.BadMessage, error: 'ping.clientTimeMs must be a finite number within ±1000000000000000, got an object' });
    expect(errorOf(conversion(valueOfMap, (w) => w.arrayHeader(2).int(ClientOpcode.SnapshotAck, 'fix'))).error).toBe('ack.tick must be an integer tick in [0, 4294967295], got an object');
    const hello = new MsgpackWriter().arrayHeader(4).int(ClientOpcode.Hello, 'fix').mapHeader(1).str('toString').int(1, 'fix').str('Ada').nil().finish();
    expect(errorOf(hello).error).toBe('hello.version must be an integer in [0, 65535], got an object');
    const input = new MsgpackWriter().arrayHeader(3).int(ClientOpcode.Input, 'fix').mapHeader(1).str('valueOf').int(1, 'fix').arrayHeader(0).finish();
    expect(errorOf(input).error).toBe('input.firstTick must be an integer tick in [0, 4294967295], got an object');
    const yaw = new MsgpackWriter().arrayHeader(3).int(ClientOpcode.Input, 'fix').int(5, 'fix').arrayHeader(1).arrayHeader(5).int(0, 'fix').int(0, 'fix').mapHeader(1).str('toString').int(1, 'fix').int(0, 'fix').int(0, 'fix').finish();
    expect(errorOf(yaw).error).toBe('input.commands[0] (tick 5): yaw must be a finite number, got an object');
    const proto = new MsgpackWriter().arrayHeader(2).int(ClientOpcode.Ping, 'fix').mapHeader(1).str('__proto__').mapHeader(0).finish();
    expect(errorOf(proto)).toEqual({ code: ErrorCode.Malformed, error: 'not a plain msgpack value: byte 3: the map key "__proto__" is not accepted' });
  });

  it('keeps −0 and fractions out of accepted commands: they arrive as canonical integers', () => {
    const w = new MsgpackWriter().arrayHeader(3).int(ClientOpcode.Input, 'fix').int(9, 'fix').arrayHeader(1).arrayHeader(5);
    w.f64(-0.3).f64(-0).f32(-0.25).f64(-0.4999).int(0, 'i64');
    const r = decodeClientMessage(w.finish());
    expect(r.ok).toBe(true);
    if (!r.ok || r.message.type !== 'input') return;
    const c = r.message.commands[0];
    expect([c.moveX, c.moveZ, c.yaw, c.pitch, c.buttons].every((v) => Object.is(v, 0))).toBe(true);
  });

  it('never throws over 40,000 generated hostile frames; what it accepts is canonical and re-encodes to itself', () => {
    const rng = new Prng(0x5eed);
    const counts: Record<string, number> = {};
    const problems: string[] = [];
    const codes = new Set<string>(Object.values(ErrorCode));
    for (let i = 0; i < 40_000; i++) {
      const frame = hostileFrame(rng, 50_000);
      let r: ReturnType<typeof decodeClientMessage>;
      try {
        r = decodeClientMessage(frame.data);
      } catch (error) {
        problems.push(`threw ${(error as Error).message} on ${frameHex(frame)}`);
        continue;
      }
      const key = `${frame.kind}:${r.ok ? 'ok' : r.code}`;
      counts[key] = (counts[key] ?? 0) + 1;
      if (!r.ok) {
        if (!codes.has(r.code) || typeof r.error !== 'string' || r.error.includes('[object') || r.error.length > 400) problems.push(`odd rejection ${JSON.stringify(r)} of ${frameHex(frame)}`);
        continue;
      }
      const again = decodeClientMessage(encodeClientMessage(r.message));
      if (!again.ok || JSON.stringify(again.message) !== JSON.stringify(r.message)) problems.push(`does not round-trip: ${frameHex(frame)}`);
      if (r.message.type === 'input' && !canonical(r.message)) problems.push(`non-canonical input from ${frameHex(frame)}`);
    }
    expect(problems.slice(0, 5)).toEqual([]);
    // Every kind of frame was generated, and the generator reaches acceptance as well as every refusal path.
    const kinds = new Set(Object.keys(counts).map((k) => k.split(':')[0] as FrameKind));
    expect(kinds.size).toBe(9);
    for (const code of [ErrorCode.Malformed, ErrorCode.Oversize, ErrorCode.BadMessage, ErrorCode.BadInput]) expect(Object.keys(counts).some((k) => k.endsWith(`:${code}`)), code).toBe(true);
    expect(counts['edge-message:ok']).toBeGreaterThan(2000);
  });
});

function canonical(m: Extract<ClientMessage, { type: 'input' }>): boolean {
  return m.commands.every((c) => Object.values(c).every((v) => Number.isInteger(v) && !Object.is(v, -0)));
}
