// Decodes server→client frames on the client: msgpack structure, opcode, field types, descriptors and events are
// checked, so a broken or hostile server produces a clear error result instead of an exception deep inside the client.
import { describeValue } from '../sim/describe-value.ts';
import type { SimEvent } from '../sim/types.ts';
import { decodeFrame, MAX_SERVER_FRAME_DEPTH, toBytes } from './codec.ts';
import { unpackDescriptors } from './descriptor-codec.ts';
import { checkGameStateValues, unpackGameSchema, type GameSchemaInfo } from './game-schema-codec.ts';
import { validateInputCommand } from '../sim/input.ts';
import type { PlayerJoin } from '../sim/types.ts';
import { MAX_INPUT_DELAY_TICKS, MAX_NAME_LENGTH, MAX_TOKEN_LENGTH, TOKEN_PATTERN } from './limits.ts';
import { isNetMode, MAX_CHECKPOINT_BYTES, type CheckpointMessage, type NetMode, type RecordMessage } from './predict-messages.ts';
import { MAX_RECORD_MEMBERSHIP_CHANGES, type PlayerInputState } from './record-delta.ts';
import { PROTOCOL_VERSION, ServerOpcode, type ByeReason, type ErrorCode } from './opcodes.ts';
import type { ScenarioInfo, ServerMessage, SnapshotMessage, WelcomeMessage } from './server-messages.ts';

/**
 * A decoded server message, or why it could not be decoded; `serverVersion` is set when the frame is a welcome of
 * another protocol version (its other fields are not read: their shape may differ).
 */
export type ServerDecodeResult = { ok: true; message: ServerMessage } | { ok: false; error: string; serverVersion?: number };

class DecodeError extends Error {}

function need(cond: boolean, message: string): asserts cond {
  if (!cond) throw new DecodeError(message);
}

function isObject(v: unknown): v is Record<string, unknown> {
  return v !== null && typeof v === 'object' && !Array.isArray(v) && !ArrayBuffer.isView(v);
}

function num(v: unknown, what: string): number {
  need(typeof v === 'number' && Number.isFinite(v), `${what} must be a finite number, got ${describeValue(v)}`);
  return v;
}

function int(v: unknown, what: string, min = 0): number {
  need(typeof v === 'number' && Number.isInteger(v) && v >= min, `${what} must be an integer ≥ ${min}, got ${describeValue(v)}`);
  return v;
}

function str(v: unknown, what: string): string {
  need(typeof v === 'string', `${what} must be a string`);
  return v;
}

function bool(v: unknown, what: string): boolean {
  need(typeof v === 'boolean', `${what} must be true or false`);
  return v;
}

function token(v: unknown, what: string): string {
  need(typeof v === 'string' && TOKEN_PATTERN.test(v), `${what} must be a token of 1-${MAX_TOKEN_LENGTH} characters of A-Z a-z 0-9 _ . -`);
  return v;
}

function vec3(v: unknown, what: string): { x: number; y: number; z: number } {
  need(isObject(v), `${what} must be an {x, y, z} object`);
  return { x: num(v.x, `${what}.x`), y: num(v.y, `${what}.y`), z: num(v.z, `${what}.z`) };
}

function decodeScenario(v: unknown): ScenarioInfo {
  need(isObject(v), 'welcome.scenario must be an object');
  need(isObject(v.params), 'welcome.scenario.params must be an object');
  const params: Record<string, number> = {};
  for (const [k, p] of Object.entries(v.params)) params[k] = num(p, `welcome.scenario.params.${k}`);
  need(isObject(v.bounds), 'welcome.scenario.bounds must be {min, max}');
  const info: ScenarioInfo = {
    name: str(v.name, 'welcome.scenario.name'),
    description: str(v.description, 'welcome.scenario.description'),
    params,
    bounds: { min: vec3(v.bounds.min, 'welcome.scenario.bounds.min'), max: vec3(v.bounds.max, 'welcome.scenario.bounds.max') },
  };
  let game: GameSchemaInfo;
  try {
    game = unpackGameSchema(v, 'welcome.scenario');
  } catch (err) {
    throw new DecodeError((err as Error).message);
  }
  if (Object.keys(game).length > 0) info.game = game;
  return info;
}

function decodeWelcome(v: unknown): WelcomeMessage {
  need(isObject(v), 'welcome must carry an object');
  const fmt = v.snapshotFormat;
  need(isObject(fmt) && Array.isArray(fmt.positionSteps) && fmt.positionSteps.length === 3, 'welcome.snapshotFormat must be {positionSteps: [x, y, z], rotationBits}');
  const positionSteps = fmt.positionSteps.map((s: unknown, i: number) => int(s, `welcome.snapshotFormat.positionSteps[${i}]`, 1)) as [number, number, number];
  return {
    type: 'welcome',
    protocolVersion: int(v.protocolVersion, 'welcome.protocolVersion'),
    playerId: int(v.playerId, 'welcome.playerId'),
    roomId: str(v.roomId, 'welcome.roomId'),
    tick: int(v.tick, 'welcome.tick'),
    tickRateHz: num(v.tickRateHz, 'welcome.tickRateHz'),
    snapshotRateHz: num(v.snapshotRateHz, 'welcome.snapshotRateHz'),
    scenario: decodeScenario(v.scenario),
    snapshotFormat: { positionSteps, rotationBits: int(fmt.rotationBits, 'welcome.snapshotFormat.rotationBits') },
    staticBodies: unpackDescriptors(v.staticBodies, 'welcome.staticBodies'),
    dynamicBodies: unpackDescriptors(v.dynamicBodies, 'welcome.dynamicBodies'),
    resumeToken: v.resumeToken === null ? null : token(v.resumeToken, 'welcome.resumeToken'),
    resumeGraceMs: int(v.resumeGraceMs, 'welcome.resumeGraceMs'),
    resumed: bool(v.resumed, 'welcome.resumed'),
    netMode: netMode(v.netMode, 'welcome.netMode'),
    inputDelayTicks: inputDelay(v.inputDelayTicks),
  };
}

function inputDelay(v: unknown): number {
  const ticks = int(v, 'welcome.inputDelayTicks');
  need(ticks <= MAX_INPUT_DELAY_TICKS, `welcome.inputDelayTicks must be at most ${MAX_INPUT_DELAY_TICKS}, got ${ticks}`);
  return ticks;
}

function netMode(v: unknown, what: string): NetMode {
  need(isNetMode(v), `${what} must be 'snapshot' or 'predict', got ${describeValue(v)}`);
  return v;
}

function binary(v: unknown, what: string, maxBytes: number): Uint8Array {
  need(v instanceof Uint8Array, `${what} must be binary`);
  need(v.byteLength <= maxBytes, `${what} is larger than ${maxBytes} bytes`);
  // A plain Uint8Array view (Node's msgpackr hands out Buffers).
  return new Uint8Array(v.buffer, v.byteOffset, v.byteLength);
}

function decodeCheckpoint(value: unknown[]): CheckpointMessage {
  need(value.length === 5, `checkpoint must have 4 fields, got ${value.length - 1}`);
  const seed = value[2];
  need(typeof seed === 'string' || (typeof seed === 'number' && Number.isInteger(seed) && seed >= 0 && seed <= 0xffffffff), 'checkpoint.seed must be a string or an integer in [0, 2^32)');
  need(Array.isArray(value[4]) && value[4].length <= MAX_RECORD_MEMBERSHIP_CHANGES * 64, 'checkpoint.inputs must be an array');
  const inputs: PlayerInputState[] = (value[4] as unknown[]).map((row, i) => {
    const what = `checkpoint.inputs[${i}]`;
    need(Array.isArray(row) && (row.length === 7 || row.length === 8), `${what} must be [playerId, moveX, moveZ, yaw, pitch, buttons, yawStep, game?]`);
    need(row.length === 7 || (Array.isArray(row[7]) && row[7].length > 0), `${what}.game must be a non-empty array of integers`);
    const v = validateInputCommand({ moveX: row[1], moveZ: row[2], yaw: row[3], pitch: row[4], buttons: row[5], game: row[7] });
    need(v.ok && !v.clamped, `${what} is not a valid command`);
    const yawStep = int(row[6], `${what}.yawStep`, -32768);
    need(yawStep <= 32767, `${what}.yawStep must be within ±32768`);
    return { playerId: int(row[0], `${what}.playerId`), input: v.command, yawStep };
  });
  return { type: 'checkpoint', tick: int(value[1], 'checkpoint.tick'), seed, bytes: binary(value[3], 'checkpoint.bytes', MAX_CHECKPOINT_BYTES), inputs };
}

function decodeRecord(value: unknown[]): RecordMessage {
  need(value.length >= 3 && value.length <= 5, `record must have 2 to 4 fields, got ${value.length - 1}`);
  const tickLow = int(value[1], 'record.tickLow');
  need(tickLow <= 255, 'record.tickLow must be below 256');
  const joins: PlayerJoin[] = [];
  if (value.length >= 4 && value[3] !== null) {
    need(Array.isArray(value[3]) && value[3].length <= MAX_RECORD_MEMBERSHIP_CHANGES, 'record.joins must be an array of [playerId, name]');
    for (const [i, j] of (value[3] as unknown[]).entries()) {
      need(Array.isArray(j) && j.length === 2, `record.joins[${i}] must be [playerId, name]`);
      const playerId = int(j[0], `record.joins[${i}].playerId`);
      need(playerId <= 0xffffffff, `record.joins[${i}].playerId is out of range`);
      const name = str(j[1], `record.joins[${i}].name`);
      need(name.length <= MAX_NAME_LENGTH * 4, `record.joins[${i}].name is too long`);
      joins.push({ playerId, name });
    }
  }
  let hash: string | null = null;
  if (value.length === 5) {
    const b = binary(value[4], 'record.hash', 8);
    need(b.byteLength === 8, 'record.hash must be 8 bytes');
    hash = Array.from(b, (x) => x.toString(16).padStart(2, '0')).join('');
  }
  return { type: 'record', tickLow, bits: binary(value[2], 'record.bits', 1 << 20), joins, hash };
}

/** Reads one event of a known type from its wire object (fields checked in this order; `tick` already read). */
type EventReader<T extends SimEvent['type']> = (v: Record<string, unknown>, tick: number, what: string) => Extract<SimEvent, { type: T }>;

const EVENT_READERS: { [T in SimEvent['type']]: EventReader<T> } = {
  sensorEnter: (v, tick, w) => ({ type: 'sensorEnter', tick, sensorId: num(v.sensorId, `${w}.sensorId`), bodyId: num(v.bodyId, `${w}.bodyId`), ...(v.playerId === undefined ? {} : { playerId: num(v.playerId, `${w}.playerId`) }) }),
  sensorExit: (v, tick, w) => ({ type: 'sensorExit', tick, sensorId: num(v.sensorId, `${w}.sensorId`), bodyId: num(v.bodyId, `${w}.bodyId`), ...(v.playerId === undefined ? {} : { playerId: num(v.playerId, `${w}.playerId`) }) }),
  playerJoined: (v, tick, w) => ({ type: 'playerJoined', tick, playerId: num(v.playerId, `${w}.playerId`), name: str(v.name, `${w}.name`), ...(v.bodyId === undefined ? {} : { bodyId: num(v.bodyId, `${w}.bodyId`) }) }),
  playerLeft: (v, tick, w) => ({ type: 'playerLeft', tick, playerId: num(v.playerId, `${w}.playerId`) }),
  bodySpawned: (v, tick, w) => ({ type: 'bodySpawned', tick, bodyId: num(v.bodyId, `${w}.bodyId`) }),
  bodyRemoved: (v, tick, w) => ({ type: 'bodyRemoved', tick, bodyId: num(v.bodyId, `${w}.bodyId`) }),
  scenario: (v, tick, w) => ({ type: 'scenario', tick, name: str(v.name, `${w}.name`), value: num(v.value, `${w}.value`) }),
};

function isEventType(type: unknown): type is SimEvent['type'] {
  return typeof type === 'string' && Object.prototype.hasOwnProperty.call(EVENT_READERS, type);
}

function decodeEvent(v: unknown, i: number): SimEvent {
  const what = `events[${i}]`;
  need(isObject(v), `${what} must be an object`);
  const type = v.type;
  need(isEventType(type), `${what}.type ${describeValue(type)} is not a known event`);
  return readEvent(type, v, int(v.tick, `${what}.tick`), what);
}

function readEvent<T extends SimEvent['type']>(type: T, v: Record<string, unknown>, tick: number, what: string): SimEvent {
  const read: EventReader<T> = EVENT_READERS[type];
  return read(v, tick, what);
}

function decode(value: unknown): ServerMessage {
  need(Array.isArray(value) && value.length > 0, 'a server message must be an array [opcode, ...fields]');
  const op = value[0];
  const arity = (n: number, name: string): void => need(value.length === n, `${name} must have ${n - 1} field(s), got ${value.length - 1}`);
  switch (op) {
    case ServerOpcode.Welcome:
      arity(2, 'welcome');
      return decodeWelcome(value[1]);
    case ServerOpcode.Pong:
      arity(7, 'pong');
      return {
        type: 'pong',
        clientTimeMs: num(value[1], 'pong.clientTimeMs'),
        serverTick: int(value[2], 'pong.serverTick'),
        serverTimeMs: num(value[3], 'pong.serverTimeMs'),
        missedInputTicks: int(value[4], 'pong.missedInputTicks'),
        roomTicksPerSecond: int(value[5], 'pong.roomTicksPerSecond'),
        roomSlow: bool(value[6], 'pong.roomSlow'),
      };
    case ServerOpcode.Snapshot: {
      need(value.length === 3 || value.length === 4, `snapshot must have 2 or 3 fields, got ${value.length - 1}`);
      need(value[1] instanceof Uint8Array, 'snapshot.bytes must be binary');
      const descriptors = value[2] === null ? [] : unpackDescriptors(value[2], 'snapshot.descriptors');
      const raw = value[1] as Uint8Array;
      // A plain Uint8Array view (Node's msgpackr hands out Buffers).
      const message: SnapshotMessage = { type: 'snapshot', bytes: new Uint8Array(raw.buffer, raw.byteOffset, raw.byteLength), descriptors };
      if (value.length === 4) {
        const state = checkGameStateValues(value[3]);
        need(typeof state !== 'string', `snapshot.state ${state as string}`);
        message.state = state;
      }
      return message;
    }
    case ServerOpcode.Events: {
      arity(2, 'events');
      need(Array.isArray(value[1]), 'events must carry an array');
      return { type: 'events', events: (value[1] as unknown[]).map(decodeEvent) };
    }
    case ServerOpcode.Error:
      arity(3, 'error');
      return { type: 'error', code: str(value[1], 'error.code') as ErrorCode, message: str(value[2], 'error.message') };
    case ServerOpcode.Bye:
      need(value.length === 3 || value.length === 4, `bye must have 2 or 3 fields, got ${value.length - 1}`);
      if (value.length === 3) return { type: 'bye', reason: str(value[1], 'bye.reason') as ByeReason, message: str(value[2], 'bye.message') };
      return { type: 'bye', reason: str(value[1], 'bye.reason') as ByeReason, message: str(value[2], 'bye.message'), url: str(value[3], 'bye.url') };
    case ServerOpcode.Checkpoint:
      return decodeCheckpoint(value);
    case ServerOpcode.Record:
      return decodeRecord(value);
    default:
      throw new DecodeError(`unknown server opcode ${describeValue(op)}`);
  }
}

/** The protocolVersion of a welcome frame when it is an integer other than ours, else null. */
function foreignWelcomeVersion(value: unknown): number | null {
  if (!Array.isArray(value) || value[0] !== ServerOpcode.Welcome || !isObject(value[1])) return null;
  const v = value[1].protocolVersion;
  return typeof v === 'number' && Number.isInteger(v) && v !== PROTOCOL_VERSION ? v : null;
}

/** Decodes one server frame; malformed data yields { ok: false, error } and never throws. */
export function decodeServerMessage(data: unknown): ServerDecodeResult {
  const bytes = toBytes(data);
  if (bytes === null) return { ok: false, error: 'expected a binary frame' };
  if (bytes.length > 1 && bytes[0] === ServerOpcode.Snapshot) return { ok: true, message: { type: 'snapshot', bytes: new Uint8Array(bytes.buffer, bytes.byteOffset + 1, bytes.length - 1), descriptors: [] } };
  const frame = decodeFrame(bytes, MAX_SERVER_FRAME_DEPTH);
  if (!frame.ok) return { ok: false, error: `not a plain msgpack value: ${frame.error}` };
  const foreign = foreignWelcomeVersion(frame.value);
  if (foreign !== null) return { ok: false, error: `the server speaks protocol ${foreign}, this client ${PROTOCOL_VERSION}`, serverVersion: foreign };
  try {
    return { ok: true, message: decode(frame.value) };
  } catch (e) {
    return { ok: false, error: e instanceof Error ? e.message : 'the message could not be decoded' };
  }
}
