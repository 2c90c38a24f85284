// Checks every client→server frame: size, msgpack structure (plain types, bounded depth), opcode, arity, field types
// and ranges, finite numbers, and each input command through the one validator (validateInputCommand). Total: never
// throws for any bytes, and error texts describe values without running any of their code (describeValue).
import { describeValue } from '../sim/describe-value.ts';
import { checkGameMessageShape } from '../sim/game-messages.ts';
import { validateInputFields, type InputCommand } from '../sim/input.ts';
import type { ClientMessage, HelloMessage, InputMessage } from './client-messages.ts';
import { decodeFrame, toBytes } from './codec.ts';
import { readInputFrame } from './input-frame-reader.ts';
import {
  MAX_CLIENT_FRAME_DEPTH,
  MAX_CLIENT_MESSAGE_BYTES,
  MAX_CLIENT_TIME_MS,
  MAX_INPUT_COMMANDS_PER_MESSAGE,
  MAX_NAME_LENGTH,
  MAX_TICK,
  MAX_TOKEN_LENGTH,
  ROOM_ID_PATTERN,
  TOKEN_PATTERN,
} from './limits.ts';
import { ClientOpcode, ErrorCode, PROTOCOL_VERSION } from './opcodes.ts';
import { isNetMode } from './predict-messages.ts';

/** A checked client message, or why it was refused (an ErrorCode and a sentence naming the field). */
export type ClientDecodeResult =
  | { ok: true; message: ClientMessage; /** Input commands the validator clamped into range. */ clampedCommands: number }
  | { ok: false; code: ErrorCode; error: string };

type Failure = { ok: false; code: ErrorCode; error: string };

function bad(error: string, code: ErrorCode = ErrorCode.BadMessage): Failure {
  return { ok: false, code, error };
}

function isTick(v: unknown): v is number {
  return typeof v === 'number' && Number.isInteger(v) && v >= 0 && v <= MAX_TICK;
}

// Control characters (C0, DEL, C1) and the bidirectional overrides/isolates that can disguise a name.
const FORBIDDEN_NAME_CHARS = /[\u0000-\u001f\u007f-\u009f\u202a-\u202e\u2066-\u2069]/;

/** Checks a display name; returns the trimmed name or an error sentence. */
export function checkPlayerName(raw: unknown): { ok: true; name: string } | { ok: false; error: string } {
  if (typeof raw !== 'string') return { ok: false, error: `name must be a string, got ${describeValue(raw)}` };
  const name = raw.trim();
  if (name.length === 0) return { ok: false, error: 'name must not be empty' };
  if (name.length > MAX_NAME_LENGTH) return { ok: false, error: `name must be at most ${MAX_NAME_LENGTH} characters, got ${name.length}` };
  if (FORBIDDEN_NAME_CHARS.test(name)) return { ok: false, error: 'name must not contain control or direction-override characters' };
  return { ok: true, name };
}

/** Checks a room id (null allowed: the default room). */
export function checkRoomId(raw: unknown): { ok: true; room: string | null } | { ok: false; error: string } {
  if (raw === null || raw === undefined) return { ok: true, room: null };
  if (typeof raw !== 'string' || !ROOM_ID_PATTERN.test(raw)) return { ok: false, error: 'room must be null or 1-64 characters of A-Z a-z 0-9 _ -' };
  return { ok: true, room: raw };
}

/** Whether v is a msgpack map decoded as a plain object (not an array, binary or anything with another prototype). */
function isPlainMap(v: unknown): v is Record<string, unknown> {
  if (v === null || typeof v !== 'object' || Array.isArray(v) || ArrayBuffer.isView(v)) return false;
  const proto: unknown = Object.getPrototypeOf(v);
  return proto === Object.prototype || proto === null;
}

const HELLO_OPTIONS = ['seatToken', 'resumeToken'] as const;

/**
 * hello: [1, version, name, room] or [1, version, name, room, {seatToken?, resumeToken?}]. The version is checked
 * first, so a client of any other version gets version-mismatch whatever the shape of the rest of its hello.
 */
function decodeHello(fields: unknown[]): ClientDecodeResult {
  const version = fields[1];
  if (typeof version !== 'number' || !Number.isInteger(version) || version < 0 || version > 0xffff) return bad(`hello.version must be an integer in [0, 65535], got ${describeValue(version)}`);
  if (version !== PROTOCOL_VERSION) {
    return bad(`this server speaks protocol ${PROTOCOL_VERSION} and the client sent protocol ${version}: use a client built for protocol ${PROTOCOL_VERSION}`, ErrorCode.VersionMismatch);
  }
  if (fields.length !== 4 && fields.length !== 5) return bad(`hello must have 3 or 4 fields, got ${fields.length - 1}`);
  const name = checkPlayerName(fields[2]);
  if (!name.ok) return bad(`hello.${name.error}`);
  if (fields[3] === undefined) return bad('hello.room must be a room id or null');
  const room = checkRoomId(fields[3]);
  if (!room.ok) return bad(`hello.${room.error}`);
  const message: HelloMessage = { type: 'hello', version, name: name.name, room: room.room };
  const options = fields[4];
  if (options !== undefined && options !== null) {
    if (!isPlainMap(options)) return bad(`hello.options must be a map {seatToken?, resumeToken?}, got ${describeValue(options)}`);
    for (const key of Object.keys(options)) {
      if (!(HELLO_OPTIONS as readonly string[]).includes(key)) return bad(`hello.options has no field ${describeValue(key)} (known: ${HELLO_OPTIONS.join(', ')})`);
    }
    for (const key of HELLO_OPTIONS) {
      if (!Object.hasOwn(options, key)) continue;
      const token: unknown = options[key];
      if (typeof token !== 'string' || !TOKEN_PATTERN.test(token)) return bad(`hello.options.${key} must be 1-${MAX_TOKEN_LENGTH} characters of A-Z a-z 0-9 _ . -, got ${describeValue(token)}`);
      message[key] = token;
    }
  }
  return { ok: true, message, clampedCommands: 0 };
}

function arity(fields: unknown[], n: number, name: string): Failure | null {
  return fields.length === n ? null : bad(`${name} must have ${n - 1} field(s), got ${fields.length - 1}`);
}

/** input: [2, firstTick, commands] or [2, firstTick, commands, ackTick] (protocol 7: a snapshot ack riding along). */
function decodeInput(fields: unknown[]): ClientDecodeResult {
  if (fields.length !== 3 && fields.length !== 4) return bad(`input must have 2 or 3 fields, got ${fields.length - 1}`);
  const firstTick = fields[1];
  const list = fields[2];
  const ackTick = fields[3];
  if (fields.length === 4 && !isTick(ackTick)) return bad(`input.ackTick must be an integer tick in [0, ${MAX_TICK}], got ${describeValue(ackTick)}`);
  if (!isTick(firstTick)) return bad(`input.firstTick must be an integer tick in [0, ${MAX_TICK}], got ${describeValue(firstTick)}`, ErrorCode.BadInput);
  if (!Array.isArray(list) || list.length === 0 || list.length > MAX_INPUT_COMMANDS_PER_MESSAGE) {
    return bad(`input.commands must be an array of 1..${MAX_INPUT_COMMANDS_PER_MESSAGE} commands`, ErrorCode.BadInput);
  }
  if (firstTick + list.length - 1 > MAX_TICK) return bad('input.commands run past the largest tick', ErrorCode.BadInput);
  const commands: InputCommand[] = [];
  let clamped = 0;
  for (let i = 0; i < list.length; i++) {
    const c = list[i];
    if (!Array.isArray(c) || (c.length !== 5 && c.length !== 6)) return bad(`input.commands[${i}] must be [moveX, moveZ, yaw, pitch, buttons] or [moveX, moveZ, yaw, pitch, buttons, [game…]]`, ErrorCode.BadInput);
    const v = validateInputFields(c[0], c[1], c[2], c[3], c[4], c.length === 6 ? c[5] : undefined);
    if (!v.ok) return bad(`input.commands[${i}] (tick ${firstTick + i}): ${v.error}`, ErrorCode.BadInput);
    if (v.clamped) clamped++;
    commands.push(v.command);
  }
  const message: InputMessage = { type: 'input', firstTick, commands };
  if (fields.length === 4) message.ackTick = ackTick as number;
  return { ok: true, message, clampedCommands: clamped };
}

/** Decodes and checks one client frame; every failure is a result, never an exception. */
export function decodeClientMessage(data: unknown, maxBytes: number = MAX_CLIENT_MESSAGE_BYTES): ClientDecodeResult {
  if (typeof data === 'string') return bad('text frames are not accepted: send binary msgpack', ErrorCode.Malformed);
  const bytes = toBytes(data);
  if (bytes === null) return bad(`expected binary data, got ${describeValue(data)}`, ErrorCode.Malformed);
  if (bytes.length > maxBytes) return bad(`message of ${bytes.length} bytes exceeds the ${maxBytes}-byte limit`, ErrorCode.Oversize);
  if (bytes.length === 0) return bad('empty message', ErrorCode.Malformed);
  // A playing client's input frame is read without the general decoder (the same fields, checked the same way).
  const input = readInputFrame(bytes);
  if (input !== null) return decodeInput(input);
  const frame = decodeFrame(bytes, MAX_CLIENT_FRAME_DEPTH);
  if (!frame.ok) return bad(`not a plain msgpack value: ${frame.error}`, ErrorCode.Malformed);
  const value = frame.value;
  if (!Array.isArray(value) || value.length === 0) return bad(`message must be an array [opcode, ...fields], got ${describeValue(value)}`);
  const op = value[0];
  switch (op) {
    case ClientOpcode.Hello:
      return decodeHello(value);
    case ClientOpcode.Input:
      return decodeInput(value);
    case ClientOpcode.SnapshotAck: {
      const wrong = arity(value, 2, 'ack');
      if (wrong) return wrong;
      if (!isTick(value[1])) return bad(`ack.tick must be an integer tick in [0, ${MAX_TICK}], got ${describeValue(value[1])}`);
      return { ok: true, message: { type: 'ack', tick: value[1] }, clampedCommands: 0 };
    }
    case ClientOpcode.Ping: {
      const wrong = arity(value, 2, 'ping');
      if (wrong) return wrong;
      const t = value[1];
      if (typeof t !== 'number' || !Number.isFinite(t) || Math.abs(t) > MAX_CLIENT_TIME_MS) return bad(`ping.clientTimeMs must be a finite number within ±${MAX_CLIENT_TIME_MS}, got ${describeValue(t)}`);
      return { ok: true, message: { type: 'ping', clientTimeMs: t }, clampedCommands: 0 };
    }
    case ClientOpcode.GameMessage: {
      const wrong = value.length === 4 ? null : arity(value, 3, 'game');
      if (wrong) return wrong;
      const shape = checkGameMessageShape(value[1], value[2]);
      if (!shape.ok) return bad(`game.${shape.error}`);
      if (value.length === 3) return { ok: true, message: { type: 'game', name: shape.name, payload: shape.payload }, clampedCommands: 0 };
      if (!isTick(value[3])) return bad(`game.tick must be an integer tick in [0, ${MAX_TICK}], got ${describeValue(value[3])}`);
      return { ok: true, message: { type: 'game', name: shape.name, payload: shape.payload, tick: value[3] }, clampedCommands: 0 };
    }
    case ClientOpcode.Bye: {
      const wrong = arity(value, 1, 'bye');
      if (wrong) return wrong;
      return { ok: true, message: { type: 'bye' }, clampedCommands: 0 };
    }
    case ClientOpcode.Resync: {
      const wrong = arity(value, 1, 'resync');
      if (wrong) return wrong;
      return { ok: true, message: { type: 'resync' }, clampedCommands: 0 };
    }
    case ClientOpcode.NetMode: {
      const wrong = arity(value, 2, 'netMode');
      if (wrong) return wrong;
      if (!isNetMode(value[1])) return bad(`netMode.mode must be 'snapshot' or 'predict', got ${describeValue(value[1])}`);
      return { ok: true, message: { type: 'netMode', mode: value[1] }, clampedCommands: 0 };
    }
    default:
      return bad(`unknown opcode ${describeValue(op)}`);
  }
}
