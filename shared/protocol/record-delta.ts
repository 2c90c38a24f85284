// Delta coding of confirmed tick input records for predict mode. Both ends keep the same per-player state (the last
// command and the last non-zero yaw step); a record goes out as bits: its leaves, then one "changed" bit per player
// present after the tick's leaves and joins and, for changed ones, only the fields that changed (yaw as the change of
// the turning rate). Joins travel beside the bits (names are rare and text). A decoded record names every present
// player's command (an absent one is the repeat the simulation would apply). For a scenario using the game API the
// commands carry their game input values and the record its game messages (record-game-bits.ts). Bad bits give an
// Error, not a state.
import { describeValue } from '../sim/describe-value.ts';
import { BUTTON_MASK, MOVE_STEPS, NEUTRAL_INPUT, PITCH_STEPS, validateInputCommand, YAW_STEPS, type InputCommand } from '../sim/input.ts';
import type { PlayerCommand, PlayerJoin, TickInputRecord } from '../sim/types.ts';
import { BitReader, BitWriter } from './bit-stream.ts';
import { canonicalGame, gameDiffers, NO_GAME_LAYOUT, readGameMessages, readGameValues, writeGameMessages, writeGameValues, type RecordGameLayout } from './record-game-bits.ts';

/** One player's coder state: the command its next record is compared with, and its last yaw step. */
export interface PlayerInputState {
  playerId: number;
  input: InputCommand;
  /** The last non-zero yaw change (steps, wrapped to ±YAW_STEPS/2). */
  yawStep: number;
}

/** Most joins or leaves one decoded record may carry. */
export const MAX_RECORD_MEMBERSHIP_CHANGES = 1024;

const FIELD_MOVE_X = 1;
const FIELD_MOVE_Z = 2;
const FIELD_YAW = 4;
const FIELD_PITCH = 8;
const FIELD_BUTTONS = 16;
const FIELD_GAME = 32;
const YAW_ORDER = 2;
const PITCH_ORDER = 4;
const BUTTON_BITS = 4;

function wrapYaw(delta: number): number {
  const half = YAW_STEPS / 2;
  return ((((delta + half) % YAW_STEPS) + YAW_STEPS) % YAW_STEPS) - half;
}

function copyInput(c: InputCommand): InputCommand {
  return c.game === undefined ? { ...c } : { ...c, game: [...c.game] };
}

function copyState(s: PlayerInputState): PlayerInputState {
  return { playerId: s.playerId, input: copyInput(s.input), yawStep: s.yawStep };
}

/** The coder state of one end of a predict-mode stream; encode() on the server, decode() on the client. */
export class RecordDeltaCoder {
  private players: PlayerInputState[];
  private readonly layout: RecordGameLayout;

  /**
   * Starts from a checkpoint's player states (any order; ids unique), or empty (a room at tick 0). `layout`: the
   * scenario's game input fields and message kinds (both ends must use the same); a state's game values must fit it.
   */
  constructor(initial: readonly PlayerInputState[] = [], layout: RecordGameLayout = NO_GAME_LAYOUT) {
    this.layout = layout;
    this.players = initial.map(copyState).sort((a, b) => a.playerId - b.playerId);
    for (let i = 0; i < this.players.length; i++) {
      const p = this.players[i];
      if (i > 0 && p.playerId === this.players[i - 1].playerId) throw new Error(`RecordDeltaCoder: player ${p.playerId} appears twice`);
      const game = p.input.game ?? [];
      const fields = layout.fields;
      if (game.length > 0 && (game.length !== fields.length || game.some((v, j) => !Number.isInteger(v) || v < fields[j].min || v > fields[j].max))) {
        throw new Error(`RecordDeltaCoder: player ${p.playerId}'s game input (${game.length} values) does not fit the scenario's fields ${fields.map((f) => `${f.name} [${f.min}, ${f.max}]`).join(', ') || '(none)'}`);
      }
      p.input = this.canonical(p.input);
    }
  }

  /** Copies of every player's state, ascending id (what a checkpoint message carries). */
  state(): PlayerInputState[] {
    return this.players.map(copyState);
  }

  /** The command a player's next record is compared with (its last confirmed one). */
  inputOf(playerId: number): InputCommand | undefined {
    return this.players.find((p) => p.playerId === playerId)?.input;
  }

  /** Encodes the next record (a valid record: e.g. the one the room stepped) and advances the state. */
  encode(record: TickInputRecord): { bits: Uint8Array; joins: PlayerJoin[] } {
    const w = new BitWriter(32);
    this.write(w, record);
    return { bits: w.finish(), joins: record.joins.map((j) => ({ playerId: j.playerId, name: j.name })) };
  }

  /**
   * Advances the state past a record exactly as encode() would, without making its bits (a room whose members take
   * no records yet keeps its coder current for the checkpoint a predicting member starts from).
   */
  advance(record: TickInputRecord): void {
    this.write(DISCARD, record);
  }

  private write(w: BitWriter, record: TickInputRecord): void {
    w.writeExpGolomb(record.leaves.length, 0);
    for (const id of record.leaves) w.writeBits(id, 32);
    // Most ticks nobody leaves or joins: the players stay as they are (already ascending).
    const present = record.leaves.length === 0 && record.joins.length === 0 ? this.players : this.membersAfter(record);
    const gameBit = this.layout.fields.length > 0;
    // A player without a command repeats its last one (as the simulation does): coded as unchanged. Commands come in
    // ascending player id (a room's records do): matched in one walk, else through a map.
    const commands = record.commands;
    let c = 0;
    let ascending = true;
    for (let i = 1; i < commands.length && ascending; i++) ascending = commands[i - 1].playerId < commands[i].playerId;
    const given = ascending ? null : new Map(commands.map((x) => [x.playerId, x.input]));
    // Every command must name a present player; checked before any state changes.
    if (given) {
      const ids = new Set(present.map((p) => p.playerId));
      for (const id of given.keys()) if (!ids.has(id)) throw notInGame(record.tick, id);
    } else {
      for (const p of present) if (c < commands.length && commands[c].playerId === p.playerId) c++;
      if (c < commands.length) throw notInGame(record.tick, commands.find((x) => !present.some((p) => p.playerId === x.playerId))!.playerId);
      c = 0;
    }
    for (const p of present) {
      let input = p.input;
      if (given) input = given.get(p.playerId) ?? input;
      else if (c < commands.length && commands[c].playerId === p.playerId) input = commands[c++].input;
      writeCommand(w, p, this.canonical(input), gameBit);
    }
    if (this.layout.kinds.length > 0) writeGameMessages(w, record.messages ?? [], present.map((p) => p.playerId), this.layout.kinds, record.tick);
    else if ((record.messages?.length ?? 0) > 0) throw new Error(`RecordDeltaCoder.encode: tick ${record.tick} has game messages but the scenario declares none`);
    this.players = present;
  }

  /** The players after a record's leaves and joins, ascending id. */
  private membersAfter(record: TickInputRecord): PlayerInputState[] {
    const leaving = new Set(record.leaves);
    return this.players.filter((p) => !leaving.has(p.playerId)).concat(record.joins.map((j) => this.joined(j))).sort((a, b) => a.playerId - b.playerId);
  }

  /** Decodes the record of `tick` and advances the state; throws a clear Error (state unchanged) on bad data. */
  decode(tick: number, bits: Uint8Array, joins: readonly PlayerJoin[]): TickInputRecord {
    const r = new BitReader(bits);
    const leaveCount = r.readExpGolomb(0);
    if (leaveCount > Math.min(this.players.length, MAX_RECORD_MEMBERSHIP_CHANGES)) throw new Error(`record of tick ${tick}: ${leaveCount} leaves but ${this.players.length} players`);
    const leaves: number[] = [];
    for (let i = 0; i < leaveCount; i++) {
      const id = r.readBits(32);
      if (leaves.length > 0 && id <= leaves[leaves.length - 1]) throw new Error(`record of tick ${tick}: leaves must be ascending and unique`);
      if (!this.players.some((p) => p.playerId === id)) throw new Error(`record of tick ${tick}: player ${id} leaves but is not in the game`);
      leaves.push(id);
    }
    if (joins.length > MAX_RECORD_MEMBERSHIP_CHANGES) throw new Error(`record of tick ${tick}: too many joins`);
    const leaving = new Set(leaves);
    const staying = this.players.filter((p) => !leaving.has(p.playerId)).map(copyState);
    for (let i = 0; i < joins.length; i++) {
      const id = joins[i].playerId;
      if (i > 0 && id <= joins[i - 1].playerId) throw new Error(`record of tick ${tick}: joins must be ascending and unique`);
      if (staying.some((p) => p.playerId === id)) throw new Error(`record of tick ${tick}: player ${id} joins but is already in the game`);
    }
    const present = staying.concat(joins.map((j) => this.joined(j))).sort((a, b) => a.playerId - b.playerId);
    const commands: PlayerCommand[] = present.map((p) => ({ playerId: p.playerId, input: readCommand(r, p, tick, this.layout) }));
    const messages = this.layout.kinds.length > 0 ? readGameMessages(r, present.map((p) => p.playerId), this.layout.kinds, tick) : [];
    if (r.remainingBits >= 8) throw new Error(`record of tick ${tick}: ${r.remainingBits} bits left over`);
    this.players = present;
    const out: TickInputRecord = { tick, leaves, joins: joins.map((j) => ({ playerId: j.playerId, name: j.name })), commands };
    if (messages.length > 0) out.messages = messages;
    return out;
  }

  /** A command in record form: game values present exactly when the scenario declares fields (absent ones 0). */
  private canonical(c: InputCommand): InputCommand {
    if (this.layout.fields.length === 0 && !('game' in c)) return c; // already in record form: no copy
    const game = canonicalGame(c.game, this.layout.fields);
    const { game: _dropped, ...plain } = c;
    return game === undefined ? plain : { ...plain, game };
  }

  private joined(j: PlayerJoin): PlayerInputState {
    return { playerId: j.playerId, input: this.canonical(NEUTRAL_INPUT), yawStep: 0 };
  }
}

function notInGame(tick: number, playerId: number): Error {
  return new Error(`RecordDeltaCoder.encode: tick ${tick} has a command for player ${playerId}, who is not in the game`);
}

/** A writer that keeps no bits: advance() runs the very code encode() runs, state updates and checks included. */
class DiscardingBitWriter extends BitWriter {
  constructor() {
    super(16);
  }

  override writeBits(): void {}
}
const DISCARD = new DiscardingBitWriter();

function writeCommand(w: BitWriter, p: PlayerInputState, c: InputCommand, gameBit: boolean): void {
  const last = p.input;
  let mask = 0;
  if (c.moveX !== last.moveX) mask |= FIELD_MOVE_X;
  if (c.moveZ !== last.moveZ) mask |= FIELD_MOVE_Z;
  if (c.yaw !== last.yaw) mask |= FIELD_YAW;
  if (c.pitch !== last.pitch) mask |= FIELD_PITCH;
  if (c.buttons !== last.buttons) mask |= FIELD_BUTTONS;
  if (gameDiffers(c.game, last.game)) mask |= FIELD_GAME;
  w.writeBool(mask !== 0);
  if (mask === 0) return;
  w.writeBits(mask, gameBit ? 6 : 5);
  if (mask & FIELD_MOVE_X) w.writeBits(c.moveX + MOVE_STEPS, 8);
  if (mask & FIELD_MOVE_Z) w.writeBits(c.moveZ + MOVE_STEPS, 8);
  if (mask & FIELD_YAW) {
    const step = wrapYaw(c.yaw - last.yaw);
    w.writeSignedExpGolomb(wrapYaw(step - p.yawStep), YAW_ORDER);
    p.yawStep = step;
  }
  if (mask & FIELD_PITCH) w.writeSignedExpGolomb(c.pitch - last.pitch, PITCH_ORDER);
  if (mask & FIELD_BUTTONS) w.writeBits(c.buttons, BUTTON_BITS);
  if (mask & FIELD_GAME) writeGameValues(w, last.game!, c.game!);
  p.input = copyInput(c);
}

/** Reads one player's command into `p` (a copy the caller commits only when the whole record decodes). */
function readCommand(r: BitReader, p: PlayerInputState, tick: number, layout: RecordGameLayout): InputCommand {
  if (!r.readBool()) return copyInput(p.input);
  const mask = r.readBits(layout.fields.length > 0 ? 6 : 5);
  if (mask === 0) throw new Error(`record of tick ${tick}: player ${p.playerId} marked changed with no field`);
  const c = copyInput(p.input);
  if (mask & FIELD_MOVE_X) c.moveX = r.readBits(8) - MOVE_STEPS;
  if (mask & FIELD_MOVE_Z) c.moveZ = r.readBits(8) - MOVE_STEPS;
  if (mask & FIELD_YAW) {
    const step = wrapYaw(p.yawStep + r.readSignedExpGolomb(YAW_ORDER));
    if (step === 0) throw new Error(`record of tick ${tick}: player ${p.playerId}'s yaw marked changed without a change`);
    c.yaw = (((p.input.yaw + step) % YAW_STEPS) + YAW_STEPS) % YAW_STEPS;
    p.yawStep = step;
  }
  if (mask & FIELD_PITCH) c.pitch = p.input.pitch + r.readSignedExpGolomb(PITCH_ORDER);
  if (mask & FIELD_BUTTONS) c.buttons = r.readBits(BUTTON_BITS);
  if (mask & FIELD_GAME) c.game = readGameValues(r, p.input.game!, layout.fields, `record of tick ${tick}: player ${p.playerId}`);
  const v = validateInputCommand(c);
  if (!v.ok || v.clamped || c.buttons & ~BUTTON_MASK || Math.abs(c.pitch) > PITCH_STEPS) {
    throw new Error(`record of tick ${tick}: player ${p.playerId}'s command is out of range: ${describeValue(c)}`);
  }
  p.input = v.command;
  return copyInput(v.command);
}
