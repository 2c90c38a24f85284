// Payload codecs of the input-log record types: header, tick (a TickInputRecord, compact binary), hash,
// checkpoint, end. Encoders validate and throw a clear Error; decoders throw PayloadError. Pure, no I/O.
import { MAX_COMMAND_GAME_VALUES, validateInputCommand, type InputCommand } from '../../shared/sim/input.ts';
import { checkGameMessageShape, MAX_GAME_MESSAGE_FIELDS, type GameMessage } from '../../shared/sim/game-messages.ts';
import type { PlayerCommand, PlayerJoin, TickInputRecord } from '../../shared/sim/types.ts';
import { ByteReader, ByteWriter, PayloadError } from '../../shared/byte-io.ts';
import { LOG_FORMAT_VERSION, MAX_HEADER_STRING_BYTES, MAX_NAME_BYTES, MAX_PLAYER_ID, type LogHeader } from './log-format.ts';

const SEED_NUMBER = 0;
const SEED_STRING = 1;

/** Command field-presence bits: a field is stored only when non-zero. */
const Field = { MoveX: 1, MoveZ: 2, Yaw: 4, Pitch: 8, Buttons: 16, Game: 32 } as const;
const FIELD_MASK = 63;

/** Zigzag: signed integers as unsigned varints (0, −1, 1, −2, … → 0, 1, 2, 3, …). */
const zigzag = (v: number): number => (v < 0 ? -2 * v - 1 : 2 * v);
const unzigzag = (u: number): number => (u % 2 === 1 ? -(u + 1) / 2 : u / 2);

const textEncoder = new TextEncoder();
const utf8Bytes = (text: string): number => textEncoder.encode(text).length;

function checkHeaderString(value: unknown, field: string): string {
  if (typeof value !== 'string') throw new Error(`log header: ${field} must be a string, got ${typeof value}`);
  if (utf8Bytes(value) > MAX_HEADER_STRING_BYTES) throw new Error(`log header: ${field} is longer than ${MAX_HEADER_STRING_BYTES} bytes`);
  return value;
}

function checkCount(value: unknown, field: string, max: number): number {
  if (typeof value !== 'number' || !Number.isInteger(value) || value < 0 || value > max) {
    throw new Error(`log header: ${field} must be an integer in [0, ${max}], got ${String(value)}`);
  }
  return value;
}

/** Encodes a header payload; throws a clear Error on a field out of range. */
export function encodeHeader(h: LogHeader): Uint8Array {
  if (h.formatVersion !== LOG_FORMAT_VERSION) throw new Error(`log header: this build writes format version ${LOG_FORMAT_VERSION}, not ${h.formatVersion}`);
  if (h === null || typeof h !== 'object' || h.params === null || typeof h.params !== 'object') throw new Error('log header: params must be an object');
  const w = new ByteWriter();
  w.varintPrefixedString(checkHeaderString(h.joltVersion, 'joltVersion'));
  if (checkHeaderString(h.scenario, 'scenario') === '') throw new Error('log header: scenario name is empty');
  w.varintPrefixedString(h.scenario);
  const names = Object.keys(h.params).sort();
  w.uvarint(names.length);
  for (const name of names) {
    const value = h.params[name];
    if (typeof value !== 'number' || !Number.isFinite(value)) throw new Error(`log header: parameter ${name} must be a finite number, got ${String(value)}`);
    w.varintPrefixedString(checkHeaderString(name, `parameter name "${name}"`));
    w.f64(value);
  }
  if (typeof h.seed === 'number') {
    if (!Number.isFinite(h.seed)) throw new Error(`log header: seed must be finite, got ${h.seed}`);
    w.u8(SEED_NUMBER);
    w.f64(h.seed);
  } else {
    w.u8(SEED_STRING);
    w.varintPrefixedString(checkHeaderString(h.seed, 'seed'));
  }
  w.uvarint(checkCount(h.tickRateHz, 'tickRateHz', 10_000));
  if (h.tickRateHz === 0) throw new Error('log header: tickRateHz must be positive');
  w.uvarint(checkCount(h.hashEveryTicks, 'hashEveryTicks', 0xffffffff));
  w.uvarint(checkCount(h.checkpointEveryTicks, 'checkpointEveryTicks', 0xffffffff));
  w.varintPrefixedString(checkHeaderString(h.createdBy, 'createdBy'));
  w.varintPrefixedString(checkHeaderString(h.scenarioHash, 'scenarioHash'));
  return w.finish();
}

/** Decodes a header payload (the format version comes from the prelude). */
export function decodeHeader(payload: Uint8Array, formatVersion: number): LogHeader {
  const r = new ByteReader(payload);
  const joltVersion = r.varintPrefixedString(MAX_HEADER_STRING_BYTES, 'joltVersion');
  const scenario = r.varintPrefixedString(MAX_HEADER_STRING_BYTES, 'scenario');
  if (scenario === '') throw new PayloadError('scenario name is empty');
  const count = r.uvarint('parameter count');
  const params: Record<string, number> = {};
  let prev = '';
  for (let i = 0; i < count; i++) {
    const name = r.varintPrefixedString(MAX_HEADER_STRING_BYTES, 'parameter name');
    if (i > 0 && !(name > prev)) throw new PayloadError(`parameter names not sorted/unique at "${name}"`);
    const value = r.f64(`parameter ${name}`);
    if (!Number.isFinite(value)) throw new PayloadError(`parameter ${name} is not finite`);
    params[name] = value;
    prev = name;
  }
  const kind = r.u8('seed kind');
  let seed: number | string;
  if (kind === SEED_NUMBER) {
    seed = r.f64('seed');
    if (!Number.isFinite(seed)) throw new PayloadError('seed is not finite');
  } else if (kind === SEED_STRING) {
    seed = r.varintPrefixedString(MAX_HEADER_STRING_BYTES, 'seed');
  } else {
    throw new PayloadError(`unknown seed kind ${kind}`);
  }
  const tickRateHz = r.uvarint('tick rate');
  if (tickRateHz === 0) throw new PayloadError('tick rate is 0');
  const hashEveryTicks = r.uvarint('hash interval');
  const checkpointEveryTicks = r.uvarint('checkpoint interval');
  const createdBy = r.varintPrefixedString(MAX_HEADER_STRING_BYTES, 'createdBy');
  const scenarioHash = formatVersion >= 2 ? r.varintPrefixedString(MAX_HEADER_STRING_BYTES, 'scenarioHash') : '';
  r.expectEnd('header');
  return { formatVersion, joltVersion, scenario, scenarioHash, params, seed, tickRateHz, hashEveryTicks, checkpointEveryTicks, createdBy };
}

function checkPlayerId(id: unknown, where: string): number {
  if (typeof id !== 'number' || !Number.isInteger(id) || id < 0 || id > MAX_PLAYER_ID) {
    throw new Error(`${where}: player id must be an integer in [0, ${MAX_PLAYER_ID}], got ${String(id)}`);
  }
  return id;
}

/** Validates a tick's input record against what the log can store; throws a clear Error naming the field. */
export function checkTickRecord(rec: TickInputRecord): void {
  if (rec === null || typeof rec !== 'object') throw new Error('tick record must be an object');
  if (!Number.isSafeInteger(rec.tick) || rec.tick < 0) throw new Error(`tick record: tick must be a non-negative integer, got ${String(rec.tick)}`);
  const where = `tick ${rec.tick}`;
  if (!Array.isArray(rec.leaves) || !Array.isArray(rec.joins) || !Array.isArray(rec.commands)) {
    throw new Error(`${where}: leaves, joins and commands must be arrays`);
  }
  let prev = -1;
  for (const raw of rec.leaves) prev = checkNextId(raw, prev, `${where} leaves`);
  prev = -1;
  for (const j of rec.joins) {
    if (j === null || typeof j !== 'object') throw new Error(`${where}: a join must be an object`);
    prev = checkNextId(j.playerId, prev, `${where} joins`);
    if (typeof j.name !== 'string') throw new Error(`${where}: join of player ${j.playerId} has no name string`);
    if (j.name.length > MAX_NAME_BYTES / 3 && utf8Bytes(j.name) > MAX_NAME_BYTES) throw new Error(`${where}: name of player ${j.playerId} is longer than ${MAX_NAME_BYTES} bytes`);
  }
  prev = -1;
  for (const c of rec.commands) {
    if (c === null || typeof c !== 'object') throw new Error(`${where}: a command must be an object`);
    prev = checkNextId(c.playerId, prev, `${where} commands`);
    const v = validateInputCommand(c.input);
    if (!v.ok) throw new Error(`${where}: command of player ${c.playerId} is invalid: ${v.error}`);
    if (v.clamped) throw new Error(`${where}: command of player ${c.playerId} is not a validated InputCommand (pass it through validateInputCommand first)`);
  }
  if (rec.messages === undefined) return;
  if (!Array.isArray(rec.messages)) throw new Error(`${where}: messages must be an array`);
  prev = -1;
  for (const m of rec.messages) {
    if (m === null || typeof m !== 'object') throw new Error(`${where}: a message must be an object`);
    const id = checkPlayerId(m.playerId, `${where} messages`);
    if (id < prev) throw new Error(`${where} messages: player ids must be sorted ascending (${prev} then ${id})`);
    prev = id;
    const shape = checkGameMessageShape(m.name, m.payload);
    if (!shape.ok) throw new Error(`${where}: message of player ${id}: ${shape.error}`);
  }
}

function checkNextId(id: unknown, prev: number, where: string): number {
  const v = checkPlayerId(id, where);
  if (!(v > prev)) throw new Error(`${where}: player ids must be sorted ascending and unique (${prev} then ${v})`);
  return v;
}

function writeCommand(w: ByteWriter, cmd: InputCommand): void {
  const mask =
    (cmd.moveX !== 0 ? Field.MoveX : 0) |
    (cmd.moveZ !== 0 ? Field.MoveZ : 0) |
    (cmd.yaw !== 0 ? Field.Yaw : 0) |
    (cmd.pitch !== 0 ? Field.Pitch : 0) |
    (cmd.buttons !== 0 ? Field.Buttons : 0) |
    (cmd.game !== undefined && cmd.game.length > 0 ? Field.Game : 0);
  w.u8(mask);
  if (mask & Field.MoveX) w.i8(cmd.moveX);
  if (mask & Field.MoveZ) w.i8(cmd.moveZ);
  if (mask & Field.Yaw) w.u16(cmd.yaw);
  if (mask & Field.Pitch) w.i16(cmd.pitch);
  if (mask & Field.Buttons) w.u8(cmd.buttons);
  if (mask & Field.Game) {
    w.uvarint(cmd.game!.length);
    for (const v of cmd.game!) w.uvarint(zigzag(v));
  }
}

function readGame(r: ByteReader, playerId: number): number[] {
  const n = r.uvarint('game input count');
  if (n === 0 || n > MAX_COMMAND_GAME_VALUES) throw new PayloadError(`command of player ${playerId} has ${n} game input values (1..${MAX_COMMAND_GAME_VALUES})`);
  const game: number[] = [];
  for (let i = 0; i < n; i++) game.push(unzigzag(r.uvarint('game input value')));
  return game;
}

/** Encodes a tick record payload as a fresh array (validated first). */
export function encodeTick(rec: TickInputRecord): Uint8Array {
  const w = new ByteWriter(64);
  writeTickPayload(w, rec);
  return w.finish();
}

/** Validates a tick record, then appends its payload to `w` (nothing is written if it is invalid). */
export function writeTickPayload(w: ByteWriter, rec: TickInputRecord): void {
  checkTickRecord(rec);
  w.uvarint(rec.tick);
  w.uvarint(rec.leaves.length);
  for (const id of rec.leaves) w.uvarint(id);
  w.uvarint(rec.joins.length);
  for (const j of rec.joins) {
    w.uvarint(j.playerId);
    w.varintPrefixedString(j.name);
  }
  w.uvarint(rec.commands.length);
  for (const c of rec.commands) {
    w.uvarint(c.playerId);
    writeCommand(w, c.input);
  }
  // Game messages follow only when there are any, so records without them keep their earlier bytes.
  if (rec.messages !== undefined && rec.messages.length > 0) {
    w.uvarint(rec.messages.length);
    for (const m of rec.messages) {
      w.uvarint(m.playerId);
      w.varintPrefixedString(m.name);
      w.uvarint(m.payload.length);
      for (const v of m.payload) w.uvarint(zigzag(v));
    }
  }
}

function readMessages(r: ByteReader): GameMessage[] {
  const n = r.uvarint('message count');
  if (n === 0) throw new PayloadError('trailing bytes after the commands: not a game message section (count 0)');
  const out: GameMessage[] = [];
  for (let i = 0, prev = -1; i < n; i++) {
    const playerId = r.uvarint('message player id');
    if (playerId > MAX_PLAYER_ID || playerId < prev) throw new PayloadError(`message player id ${playerId} out of range or not sorted (after ${prev})`);
    prev = playerId;
    const name = r.varintPrefixedString(64, 'message name');
    const count = r.uvarint('message payload count');
    if (count > MAX_GAME_MESSAGE_FIELDS) throw new PayloadError(`message ${name} has ${count} payload values (at most ${MAX_GAME_MESSAGE_FIELDS})`);
    const payload: number[] = [];
    for (let k = 0; k < count; k++) payload.push(unzigzag(r.uvarint('message payload value')));
    const shape = checkGameMessageShape(name, payload);
    if (!shape.ok) throw new PayloadError(`message of player ${playerId}: ${shape.error}`);
    out.push({ playerId, name, payload });
  }
  return out;
}

function readPlayerId(r: ByteReader, prev: number, what: string): number {
  const id = r.uvarint(what);
  if (id > MAX_PLAYER_ID) throw new PayloadError(`${what} ${id} exceeds ${MAX_PLAYER_ID}`);
  if (!(id > prev)) throw new PayloadError(`${what} ${id} not sorted/unique (after ${prev})`);
  return id;
}

/** Decodes a tick record payload (bytes[start, end)) into a TickInputRecord (commands re-validated). */
export function decodeTick(payload: Uint8Array, start = 0, end = payload.length): TickInputRecord {
  const r = new ByteReader(payload, start, end);
  const tick = r.uvarint('tick');
  const leaves: number[] = [];
  const nLeaves = r.uvarint('leave count');
  for (let i = 0, prev = -1; i < nLeaves; i++) {
    prev = readPlayerId(r, prev, 'leaving player id');
    leaves.push(prev);
  }
  const joins: PlayerJoin[] = [];
  const nJoins = r.uvarint('join count');
  for (let i = 0, prev = -1; i < nJoins; i++) {
    const playerId = (prev = readPlayerId(r, prev, 'joining player id'));
    joins.push({ playerId, name: r.varintPrefixedString(MAX_NAME_BYTES, 'player name') });
  }
  const commands: PlayerCommand[] = [];
  const nCommands = r.uvarint('command count');
  for (let i = 0, prev = -1; i < nCommands; i++) {
    const playerId = (prev = readPlayerId(r, prev, 'command player id'));
    const mask = r.u8('command field mask');
    if (mask & ~FIELD_MASK) throw new PayloadError(`command of player ${playerId} has unknown field bits 0x${mask.toString(16)}`);
    const input: InputCommand = {
      moveX: mask & Field.MoveX ? r.i8('moveX') : 0,
      moveZ: mask & Field.MoveZ ? r.i8('moveZ') : 0,
      yaw: mask & Field.Yaw ? r.u16('yaw') : 0,
      pitch: mask & Field.Pitch ? r.i16('pitch') : 0,
      buttons: mask & Field.Buttons ? r.u8('buttons') : 0,
    };
    if (mask & Field.Game) input.game = readGame(r, playerId);
    const v = validateInputCommand(input);
    if (!v.ok || v.clamped) throw new PayloadError(`command of player ${playerId} is out of range`);
    commands.push({ playerId, input });
  }
  if (r.remaining === 0) {
    r.expectEnd('tick record');
    return { tick, leaves, joins, commands };
  }
  const messages = readMessages(r);
  r.expectEnd('tick record');
  return { tick, leaves, joins, commands, messages };
}

function hexDigit(code: number): number {
  if (code >= 48 && code <= 57) return code - 48;
  if (code >= 97 && code <= 102) return code - 87;
  return -1;
}

function checkHash(hash: string): void {
  let ok = typeof hash === 'string' && hash.length === 16;
  for (let i = 0; ok && i < 16; i++) ok = hexDigit(hash.charCodeAt(i)) >= 0;
  if (!ok) throw new Error(`state hash must be 16 lowercase hex digits, got ${JSON.stringify(hash)}`);
}

function writeHash(w: ByteWriter, hash: string): void {
  for (let i = 0; i < 16; i += 2) w.u8((hexDigit(hash.charCodeAt(i)) << 4) | hexDigit(hash.charCodeAt(i + 1)));
}

const HEX_PAIRS = Array.from({ length: 256 }, (_, i) => i.toString(16).padStart(2, '0'));

function readHash(r: ByteReader): string {
  const b = r.raw(8, 'hash');
  return HEX_PAIRS[b[0]] + HEX_PAIRS[b[1]] + HEX_PAIRS[b[2]] + HEX_PAIRS[b[3]] + HEX_PAIRS[b[4]] + HEX_PAIRS[b[5]] + HEX_PAIRS[b[6]] + HEX_PAIRS[b[7]];
}

function checkTick(tick: number, what: string): void {
  if (!Number.isSafeInteger(tick) || tick < 0) throw new Error(`${what}: tick must be a non-negative integer, got ${String(tick)}`);
}

/** Appends a hash record payload (tick counter when hashed, 64-bit hash) to `w`; validates first. */
export function writeHashPayload(w: ByteWriter, tick: number, hash: string): void {
  checkTick(tick, 'hash record');
  checkHash(hash);
  w.uvarint(tick);
  writeHash(w, hash);
}

/** Encodes a hash record payload as a fresh array. */
export function encodeHash(tick: number, hash: string): Uint8Array {
  const w = new ByteWriter(16);
  writeHashPayload(w, tick, hash);
  return w.finish();
}

/** Decodes a hash record payload. */
export function decodeHash(payload: Uint8Array, start = 0, end = payload.length): { tick: number; hash: string } {
  const r = new ByteReader(payload, start, end);
  const tick = r.uvarint('tick');
  const hash = readHash(r);
  r.expectEnd('hash record');
  return { tick, hash };
}

/** Appends the head of a checkpoint payload (the tick counter) to `w`; the checkpoint bytes follow it. */
export function writeCheckpointHead(w: ByteWriter, tick: number, bytes: Uint8Array): void {
  checkTick(tick, 'checkpoint record');
  if (!(bytes instanceof Uint8Array)) throw new Error('checkpoint record: bytes must be a Uint8Array');
  w.uvarint(tick);
}

/** Encodes a whole checkpoint payload (tick counter, then the simulation's checkpoint bytes) as a fresh array. */
export function encodeCheckpoint(tick: number, bytes: Uint8Array): Uint8Array {
  const w = new ByteWriter(bytes.length + 8);
  writeCheckpointHead(w, tick, bytes);
  w.raw(bytes);
  return w.finish();
}

/** Decodes a checkpoint payload (the bytes are a copy, safe to keep). */
export function decodeCheckpoint(payload: Uint8Array, start = 0, end = payload.length): { tick: number; bytes: Uint8Array } {
  const r = new ByteReader(payload, start, end);
  const tick = r.uvarint('tick');
  return { tick, bytes: Uint8Array.prototype.slice.call(payload, r.offset, end) }; // a copy even when given a Buffer
}

/** Appends the end record payload (final tick counter, final state hash) to `w`; validates first. */
export function writeEndPayload(w: ByteWriter, tick: number, hash: string): void {
  checkTick(tick, 'end record');
  checkHash(hash);
  w.uvarint(tick);
  writeHash(w, hash);
}

/** Encodes the end record payload as a fresh array. */
export function encodeEnd(tick: number, hash: string): Uint8Array {
  const w = new ByteWriter(16);
  writeEndPayload(w, tick, hash);
  return w.finish();
}

/** Decodes the end record payload. */
export function decodeEnd(payload: Uint8Array, start = 0, end = payload.length): { tick: number; hash: string } {
  const r = new ByteReader(payload, start, end);
  const tick = r.uvarint('tick');
  const hash = readHash(r);
  r.expectEnd('end record');
  return { tick, hash };
}
