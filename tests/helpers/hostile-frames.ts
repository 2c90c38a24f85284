// Seeded generators of hostile client frames for the decoder property tests and the live fuzz test: random bytes,
// wrong shapes, types and arity, float edges (−0, NaN, ±Infinity), extreme ticks and ids, deep nesting, extension and
// record types, toString/valueOf/__proto__ keys, 64-bit integers, oversized and text frames. Same seed, same frames.
import { encodeClientMessage } from '../../shared/protocol/codec.ts';
import { MAX_CLIENT_MESSAGE_BYTES, MAX_INPUT_COMMANDS_PER_MESSAGE, MAX_TICK } from '../../shared/protocol/limits.ts';
import { ClientOpcode, PROTOCOL_VERSION } from '../../shared/protocol/opcodes.ts';
import type { Prng } from '../../shared/sim/prng.ts';
import { MsgpackWriter, type IntWidth } from './msgpack-writer.ts';

/** Numbers at the edges of every range the protocol checks, and of IEEE-754 itself. */
export const EDGE_NUMBERS: readonly number[] = [
  0, -0, 1, -1, 0.3, -0.3, 0.5, -0.5, -0.49, 1.5, -1.5, 126.5, 127, 127.4, 128, -127.5, -128, 255, 256, 16384.5, -16384.5,
  65535, 65535.5, 65536, -65536, 2 ** 31 - 1, 2 ** 31, -(2 ** 31), 2 ** 32 - 1, 2 ** 32, 2 ** 53 - 1, 2 ** 53, 2 ** 53 + 2,
  -(2 ** 53), 1e15, -1e15, 1e16, 1e300, -1e300, Number.MAX_VALUE, Number.MIN_VALUE, -Number.MIN_VALUE, Number.NaN,
  Number.POSITIVE_INFINITY, Number.NEGATIVE_INFINITY,
];

/** Keys that break naive code: conversions, prototype names, array-likes, our own field names. */
export const DANGEROUS_KEYS: readonly string[] = ['toString', 'valueOf', '__proto__', 'constructor', 'prototype', 'hasOwnProperty', 'toJSON', 'then', 'length', '0', 'moveX', 'type', '__defineGetter__', 'isPrototypeOf'];

/** msgpackr's own extensions (records, clones, bigint, typed arrays, errors, dates, …) and some unknown ones. */
const EXT_TYPES = [0x00, 0x42, 0x62, 0x65, 0x69, 0x70, 0x72, 0x73, 0x74, 0x78, 0xff, 0x01, 0x7f, 0x80];

/** What kind of hostility a frame carries. */
export const FRAME_KINDS = ['random-bytes', 'hostile-fields', 'edge-message', 'deep-nesting', 'extension', 'mutated', 'dangerous-keys', 'text', 'oversize'] as const;
export type FrameKind = (typeof FRAME_KINDS)[number];

/** One generated frame: binary bytes, or a string for a text frame. */
export interface HostileFrame {
  kind: FrameKind;
  data: Uint8Array | string;
}

const WEIGHTS: Record<FrameKind, number> = { 'random-bytes': 14, 'hostile-fields': 14, 'edge-message': 36, 'deep-nesting': 4, extension: 8, mutated: 10, 'dangerous-keys': 8, text: 3, oversize: 3 };

function widthsFor(n: number): IntWidth[] {
  const w: IntWidth[] = [];
  if (n >= -32 && n <= 127) w.push('fix');
  if (n >= 0) {
    if (n <= 0xff) w.push('u8');
    if (n <= 0xffff) w.push('u16');
    if (n <= 0xffff_ffff) w.push('u32');
    w.push('u64');
  }
  if (n >= -128 && n <= 127) w.push('i8');
  if (n >= -32768 && n <= 32767) w.push('i16');
  if (n >= -(2 ** 31) && n < 2 ** 31) w.push('i32');
  w.push('i64');
  return w;
}

/** Writes `n` in an encoding chosen at random among those that hold it (floats for −0 and fractions). */
export function writeNumber(w: MsgpackWriter, rng: Prng, n: number): void {
  const exactInt = Number.isInteger(n) && !Object.is(n, -0) && Math.abs(n) < 2 ** 63;
  const r = rng.int(0, 3);
  if (exactInt && r < 2) w.int(BigInt(n), rng.pick(widthsFor(n)));
  else if (r === 3 || Math.fround(n) !== n) w.f64(n);
  else w.f32(n);
}

function writeText(w: MsgpackWriter, rng: Prng): void {
  switch (rng.int(0, 5)) {
    case 0:
      w.str(rng.pick(DANGEROUS_KEYS));
      return;
    case 1:
      w.str('x'.repeat(rng.int(0, 300)), rng.next() < 0.3);
      return;
    case 2:
      w.str(String.fromCharCode(...Array.from({ length: rng.int(1, 8) }, () => rng.pick([0, 7, 0x1b, 0x7f, 0x85, 0x202e, 0x2066, 0xd800, 0xfeff, 0x41]))));
      return;
    case 3: {
      const n = rng.int(1, 12); // invalid UTF-8 bytes under a string header
      w.strHeader(n).rawBytes(Array.from({ length: n }, () => rng.int(0x80, 0xff)));
      return;
    }
    case 4:
      w.str(rng.pick(['default', 'Ada', 'character-course', 'no-such-room', '', ' ', '../etc', 'a'.repeat(65)]));
      return;
    default:
      w.strHeader(rng.int(5, 200)).raw(0x41, 0x42); // claims more bytes than follow
  }
}

/** Writes one hostile value; containers recurse until `depth` runs out. */
export function writeHostile(w: MsgpackWriter, rng: Prng, depth = 3): void {
  const scalarOnly = depth <= 0;
  switch (rng.int(0, scalarOnly ? 4 : 11)) {
    case 0:
      writeNumber(w, rng, rng.pick(EDGE_NUMBERS));
      return;
    case 1: {
      const width = rng.pick<IntWidth>(['u64', 'i64', 'u32', 'i32']);
      w.int(rng.pick([0n, 1n, -1n, 2n ** 63n - 1n, -(2n ** 63n), 2n ** 64n - 1n, 2n ** 53n + 1n, 0xffff_ffffn, BigInt(rng.nextU32())]), width);
      return;
    }
    case 2:
      writeText(w, rng);
      return;
    case 3:
      w.bin(Uint8Array.from({ length: rng.int(0, 24) }, () => rng.int(0, 255)));
      return;
    case 4:
      if (rng.next() < 0.5) w.nil();
      else w.bool(rng.next() < 0.5);
      return;
    case 5: {
      const n = rng.int(0, 5);
      w.arrayHeader(n, rng.next() < 0.2);
      for (let i = 0; i < n; i++) writeHostile(w, rng, depth - 1);
      return;
    }
    case 6: {
      const n = rng.int(0, 4);
      w.mapHeader(n, rng.next() < 0.2);
      for (let i = 0; i < n; i++) {
        const k = rng.int(0, 9);
        if (k < 7) w.str(rng.pick(DANGEROUS_KEYS));
        else if (k === 7) writeNumber(w, rng, rng.pick(EDGE_NUMBERS));
        else if (k === 8) w.arrayHeader(1).int(1, 'fix');
        else w.nil();
        writeHostile(w, rng, depth - 1);
      }
      return;
    }
    case 7:
      writeExtension(w, rng);
      return;
    case 8:
      w.raw(0xc1);
      return;
    case 9:
      // A container that claims far more values than the frame holds (an allocation bomb for a careless decoder).
      if (rng.next() < 0.5) w.arrayHeader(rng.pick([0xffff, 0xffff_ffff, 1000]), true);
      else w.mapHeader(rng.pick([0xffff, 0xffff_ffff, 1000]), true);
      w.nil();
      return;
    case 10:
      writeDeep(w, rng, rng.int(9, 300));
      return;
    default:
      w.arrayHeader(rng.int(1, 3));
      writeHostile(w, rng, depth - 1); // an array that may end early
  }
}

function writeExtension(w: MsgpackWriter, rng: Prng): void {
  const type = rng.pick(EXT_TYPES);
  const len = rng.pick([1, 2, 4, 8, 16, rng.int(0, 40)]);
  const data = Uint8Array.from({ length: len }, () => rng.int(0, 255));
  if (type === 0x72 && len >= 1) data[0] = 0x40 + rng.int(0, 3); // a record definition id
  w.ext(type, data);
  if (type === 0x72 || type === 0x69) w.arrayHeader(1).str(rng.pick(DANGEROUS_KEYS)); // a structure or target to go with it
}

function writeDeep(w: MsgpackWriter, rng: Prng, levels: number): void {
  for (let i = 0; i < levels; i++) {
    if (rng.next() < 0.8) w.arrayHeader(1);
    else w.mapHeader(1).str(rng.pick(DANGEROUS_KEYS));
  }
  w.nil();
}

/** A tick near the live one, or an extreme one. */
function hostileTick(w: MsgpackWriter, rng: Prng, tick: number): void {
  if (rng.next() < 0.6) writeNumber(w, rng, Math.max(0, tick + rng.int(-10, 140)));
  else writeNumber(w, rng, rng.pick([0, 1, MAX_TICK, MAX_TICK - 3, MAX_TICK + 1, 2 ** 53, -1, 0.5, -0, Number.NaN, tick + 0.5, 1e300]));
}

/** A command field: usually an in-range or out-of-range number (−0 and fractions included), sometimes worse. */
function hostileCommandField(w: MsgpackWriter, rng: Prng): void {
  const r = rng.next();
  if (r < 0.5) writeNumber(w, rng, rng.range(-200, 200) * (rng.next() < 0.5 ? 1 : 0.01));
  else if (r < 0.85) writeNumber(w, rng, rng.pick(EDGE_NUMBERS));
  else writeHostile(w, rng, 1);
}

function edgeMessage(w: MsgpackWriter, rng: Prng, tick: number): void {
  switch (rng.pick([ClientOpcode.Hello, ClientOpcode.Input, ClientOpcode.Input, ClientOpcode.Input, ClientOpcode.SnapshotAck, ClientOpcode.Ping, ClientOpcode.Bye, ClientOpcode.Resync, ClientOpcode.NetMode])) {
    case ClientOpcode.Hello:
      w.arrayHeader(4).int(ClientOpcode.Hello, 'fix');
      if (rng.next() < 0.7) w.int(PROTOCOL_VERSION, 'fix');
      else writeHostile(w, rng, 1);
      if (rng.next() < 0.6) w.str(`fz${rng.int(0, 999)}`);
      else writeHostile(w, rng, 1);
      if (rng.next() < 0.5) w.nil();
      else writeText(w, rng);
      return;
    case ClientOpcode.Input: {
      // [2, firstTick, commands] or, since protocol 7, [2, firstTick, commands, ackTick]; sometimes any arity.
      const arity = rng.next() < 0.9 ? rng.pick([3, 4]) : rng.int(0, 5);
      w.arrayHeader(arity).int(ClientOpcode.Input, 'fix');
      if (arity < 2) return;
      hostileTick(w, rng, tick);
      if (arity < 3) return;
      const n = rng.next() < 0.9 ? rng.int(1, 6) : rng.pick([0, MAX_INPUT_COMMANDS_PER_MESSAGE, MAX_INPUT_COMMANDS_PER_MESSAGE + 1]);
      w.arrayHeader(n);
      for (let i = 0; i < n; i++) {
        const fields = rng.next() < 0.93 ? 5 : rng.int(0, 7);
        w.arrayHeader(fields);
        for (let f = 0; f < fields; f++) hostileCommandField(w, rng);
      }
      if (arity >= 4 && rng.next() < 0.7) hostileTick(w, rng, tick);
      else if (arity >= 4) writeHostile(w, rng, 1);
      for (let i = 4; i < arity; i++) writeHostile(w, rng, 1);
      return;
    }
    case ClientOpcode.SnapshotAck:
      w.arrayHeader(2).int(ClientOpcode.SnapshotAck, 'fix');
      hostileTick(w, rng, tick);
      return;
    case ClientOpcode.Ping:
      w.arrayHeader(2).int(ClientOpcode.Ping, 'fix');
      writeNumber(w, rng, rng.next() < 0.5 ? rng.range(-1e6, 1e6) : rng.pick(EDGE_NUMBERS));
      return;
    case ClientOpcode.Resync: {
      const arity = rng.next() < 0.8 ? 1 : 2;
      w.arrayHeader(arity).int(ClientOpcode.Resync, 'fix');
      if (arity === 2) writeHostile(w, rng, 1);
      return;
    }
    case ClientOpcode.NetMode: {
      const arity = rng.next() < 0.8 ? 2 : rng.int(1, 3);
      w.arrayHeader(arity).int(ClientOpcode.NetMode, 'fix');
      for (let i = 1; i < arity; i++) {
        if (rng.next() < 0.6) w.str(rng.pick(['predict', 'snapshot', 'Predict', '']));
        else writeHostile(w, rng, 1);
      }
      return;
    }
    default:
      w.arrayHeader(rng.next() < 0.8 ? 1 : 2).int(ClientOpcode.Bye, 'fix');
  }
}

function dangerousKeys(w: MsgpackWriter, rng: Prng, tick: number): void {
  // Maps whose conversion keys are numbers, where the server expects a number: the frame that once killed it.
  const map = (): void => {
    const n = rng.int(1, 3);
    w.mapHeader(n);
    for (let i = 0; i < n; i++) {
      w.str(i === 0 ? rng.pick(['toString', 'valueOf', '__proto__']) : rng.pick(DANGEROUS_KEYS));
      writeHostile(w, rng, 1);
    }
  };
  const op = rng.pick([ClientOpcode.Hello, ClientOpcode.Input, ClientOpcode.SnapshotAck, ClientOpcode.Ping]);
  if (op === ClientOpcode.Hello) {
    w.arrayHeader(4).int(op, 'fix');
    const at = rng.int(0, 2);
    for (let i = 0; i < 3; i++) if (i === at) map(); else if (i === 0) w.int(PROTOCOL_VERSION, 'fix'); else w.str('x');
  } else if (op === ClientOpcode.Input) {
    w.arrayHeader(3).int(op, 'fix');
    if (rng.next() < 0.4) map();
    else writeNumber(w, rng, tick + 2);
    w.arrayHeader(1).arrayHeader(5);
    const at = rng.int(0, 4);
    for (let f = 0; f < 5; f++) if (f === at) map(); else w.int(0, 'fix');
  } else {
    w.arrayHeader(2).int(op, 'fix');
    map();
  }
}

function mutated(rng: Prng, tick: number): Uint8Array {
  const valid = encodeClientMessage(
    rng.next() < 0.6
      ? { type: 'input', firstTick: tick + 3, commands: [{ moveX: 1, moveZ: -127, yaw: 40000, pitch: -3, buttons: 5 }], ...(rng.next() < 0.5 ? { ackTick: tick } : {}) }
      : rng.next() < 0.5
        ? { type: 'ack', tick }
        : { type: 'hello', version: PROTOCOL_VERSION, name: 'mutant', room: 'default' },
  );
  const bytes = Array.from(valid);
  const edits = rng.int(1, 3);
  for (let i = 0; i < edits; i++) {
    const at = rng.int(0, bytes.length - 1);
    const r = rng.int(0, 2);
    if (r === 0) bytes[at] = rng.int(0, 255);
    else if (r === 1) bytes.splice(at, 1);
    else bytes.splice(at, 0, rng.int(0, 255));
  }
  return Uint8Array.from(bytes);
}

function pickKind(rng: Prng): FrameKind {
  let total = 0;
  for (const k of FRAME_KINDS) total += WEIGHTS[k];
  let r = rng.next() * total;
  for (const k of FRAME_KINDS) {
    r -= WEIGHTS[k];
    if (r < 0) return k;
  }
  return 'edge-message';
}

/** One hostile frame; `tick` (the server's tick, if known) aims inputs and acks at ticks that matter. */
export function hostileFrame(rng: Prng, tick = 0, kind: FrameKind = pickKind(rng)): HostileFrame {
  const w = new MsgpackWriter();
  switch (kind) {
    case 'random-bytes':
      return { kind, data: Uint8Array.from({ length: rng.int(0, 64) }, () => rng.int(0, 255)) };
    case 'hostile-fields': {
      const arity = rng.int(0, 6);
      w.arrayHeader(arity);
      if (arity > 0) {
        if (rng.next() < 0.8) w.int(rng.int(ClientOpcode.Hello, ClientOpcode.NetMode), 'fix');
        else writeHostile(w, rng, 1);
      }
      for (let i = 1; i < arity; i++) writeHostile(w, rng);
      break;
    }
    case 'edge-message':
      edgeMessage(w, rng, tick);
      break;
    case 'deep-nesting':
      w.arrayHeader(2).int(rng.int(ClientOpcode.Hello, ClientOpcode.NetMode), 'fix');
      writeDeep(w, rng, rng.int(5, 900));
      break;
    case 'extension':
      w.arrayHeader(rng.int(1, 3)).int(rng.int(ClientOpcode.Hello, ClientOpcode.NetMode), 'fix');
      writeExtension(w, rng);
      break;
    case 'mutated':
      return { kind, data: mutated(rng, tick) };
    case 'dangerous-keys':
      dangerousKeys(w, rng, tick);
      break;
    case 'text':
      return { kind, data: rng.pick(['{"op":1}', '', 'hello', '\u0000\u202e', '[4,{"toString":1}]', 'x'.repeat(rng.int(1, 2000))]) };
    case 'oversize': {
      const n = rng.int(MAX_CLIENT_MESSAGE_BYTES + 1, 4 * MAX_CLIENT_MESSAGE_BYTES);
      const bytes = new Uint8Array(n);
      let x = rng.nextU32() | 1;
      for (let i = 1; i < n; i++) bytes[i] = (x = Math.imul(x, 0x2c1b3c6d) + 0x297a2d39) >>> 24; // cheap filler
      bytes[0] = 0xdc; // an array header that would be plausible, then the filler
      return { kind, data: bytes };
    }
  }
  return { kind, data: w.finish() };
}

/** Hex of a frame (text frames are marked), for failure messages that let anyone replay the frame. */
export function frameHex(frame: HostileFrame): string {
  if (typeof frame.data === 'string') return `text:${JSON.stringify(frame.data.slice(0, 200))}`;
  return Buffer.from(frame.data).toString('hex');
}
