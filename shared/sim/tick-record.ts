// Validation of one tick's input record before anything of it is applied: the tick number, sorted unique player
// ids, leaves of present players, joins of absent ones, and every command re-checked by validateInputCommand and
// fitted to the scenario's game input fields, and game messages of players in the game, checked against their kinds.
import { describeValue } from './describe-value.ts';
import { fitGameInput, type GameInputField } from './game-input.ts';
import { checkGameMessage, checkGameMessageShape, MAX_GAME_MESSAGES_PER_PLAYER_TICK, type GameMessage, type GameMessageKind } from './game-messages.ts';
import { validateInputCommand, type InputCommand } from './input.ts';
import type { PlayerCommand, PlayerJoin, TickInputRecord } from './types.ts';

/** Largest player id (the input log stores ids as unsigned 32-bit integers). */
export const MAX_PLAYER_ID = 0xffffffff;
/** Longest player name, in UTF-8 bytes. */
export const MAX_PLAYER_NAME_BYTES = 1024;

function utf8Length(text: string): number {
  let n = 0;
  for (let i = 0; i < text.length; i++) {
    const c = text.charCodeAt(i);
    if (c < 0x80) n += 1;
    else if (c < 0x800) n += 2;
    else if (c >= 0xd800 && c <= 0xdbff && i + 1 < text.length) {
      n += 4;
      i++;
    } else n += 3;
  }
  return n;
}

function playerId(value: unknown, where: string): number {
  if (typeof value !== 'number' || !Number.isInteger(value) || value < 0 || value > MAX_PLAYER_ID) {
    throw new Error(`${where}: player id must be an integer in [0, ${MAX_PLAYER_ID}], got ${describeValue(value)}`);
  }
  return value;
}

function ascending(ids: number[], where: string): void {
  for (let i = 1; i < ids.length; i++) {
    if (ids[i] === ids[i - 1]) throw new Error(`${where}: player ${ids[i]} appears twice`);
    if (ids[i] < ids[i - 1]) throw new Error(`${where}: player ids must be sorted ascending (${ids[i - 1]} before ${ids[i]})`);
  }
}

function array(value: unknown, where: string): unknown[] {
  if (!Array.isArray(value)) throw new Error(`${where} must be an array`);
  return value;
}

/**
 * Checks a record for tick `expectedTick` against the players present before it; returns a clean copy or throws a
 * clear Error (nothing is applied). Commands must already be exact validated InputCommands, as the log stores them.
 */
export function validateTickRecord(
  raw: unknown,
  expectedTick: number,
  isPresent: (playerId: number) => boolean,
  gameFields: readonly GameInputField[] = [],
  kinds: readonly GameMessageKind[] = [],
): TickInputRecord {
  if (raw === null || typeof raw !== 'object' || Array.isArray(raw)) throw new Error('step: the tick input record must be an object');
  const rec = raw as Record<string, unknown>;
  if (rec.tick !== expectedTick) {
    throw new Error(`step: record for tick ${describeValue(rec.tick)} given, but the simulation is at tick ${expectedTick} (records apply in order)`);
  }
  const where = `step(tick ${expectedTick})`;
  const leaves = array(rec.leaves, `${where}: leaves`).map((id) => playerId(id, `${where} leave`));
  ascending(leaves, `${where} leaves`);
  const leaving = new Set<number>();
  for (const id of leaves) {
    if (!isPresent(id)) throw new Error(`${where}: player ${id} cannot leave, it is not in the game`);
    leaving.add(id);
  }
  const present = (id: number): boolean => !leaving.has(id) && isPresent(id);

  const joins: PlayerJoin[] = [];
  for (const j of array(rec.joins, `${where}: joins`)) {
    if (j === null || typeof j !== 'object') throw new Error(`${where}: each join must be an object {playerId, name}`);
    const jr = j as Record<string, unknown>;
    const id = playerId(jr.playerId, `${where} join`);
    if (typeof jr.name !== 'string') throw new Error(`${where}: join of player ${id} needs a name string`);
    if (utf8Length(jr.name) > MAX_PLAYER_NAME_BYTES) throw new Error(`${where}: name of player ${id} is longer than ${MAX_PLAYER_NAME_BYTES} bytes`);
    if (present(id)) throw new Error(`${where}: player ${id} cannot join, it is already in the game`);
    joins.push({ playerId: id, name: jr.name });
  }
  ascending(joins.map((j) => j.playerId), `${where} joins`);
  const joining = new Set(joins.map((j) => j.playerId));

  const commands: PlayerCommand[] = [];
  for (const c of array(rec.commands, `${where}: commands`)) {
    if (c === null || typeof c !== 'object') throw new Error(`${where}: each command must be an object {playerId, input}`);
    const cr = c as Record<string, unknown>;
    const id = playerId(cr.playerId, `${where} command`);
    if (!present(id) && !joining.has(id)) throw new Error(`${where}: command for player ${id}, who is not in the game`);
    const v = validateInputCommand(cr.input);
    if (!v.ok) throw new Error(`${where}: command of player ${id} is invalid: ${v.error}`);
    if (v.clamped) throw new Error(`${where}: command of player ${id} is out of range; pass raw input through validateInputCommand first`);
    const fit = fitGameInput(v.command, gameFields);
    if (!fit.ok) throw new Error(`${where}: command of player ${id} is invalid: ${fit.error}`);
    if (fit.clamped) throw new Error(`${where}: command of player ${id} has game input outside the declared ranges`);
    const input: InputCommand = fit.command;
    commands.push({ playerId: id, input });
  }
  ascending(commands.map((c) => c.playerId), `${where} commands`);
  const messages = validateMessages(rec.messages, where, (id) => present(id) || joining.has(id), kinds);
  return messages.length > 0 ? { tick: expectedTick, leaves, joins, commands, messages } : { tick: expectedTick, leaves, joins, commands };
}

function validateMessages(raw: unknown, where: string, inGame: (playerId: number) => boolean, kinds: readonly GameMessageKind[]): GameMessage[] {
  if (raw === undefined) return [];
  const out: GameMessage[] = [];
  let prev = -1;
  let run = 0;
  for (const m of array(raw, `${where}: messages`)) {
    if (m === null || typeof m !== 'object') throw new Error(`${where}: each message must be an object {playerId, name, payload}`);
    const mr = m as Record<string, unknown>;
    const id = playerId(mr.playerId, `${where} message`);
    if (!inGame(id)) throw new Error(`${where}: message from player ${id}, who is not in the game`);
    if (id < prev) throw new Error(`${where}: messages must be sorted by player id (${prev} before ${id})`);
    run = id === prev ? run + 1 : 1;
    if (run > MAX_GAME_MESSAGES_PER_PLAYER_TICK) throw new Error(`${where}: player ${id} has more than ${MAX_GAME_MESSAGES_PER_PLAYER_TICK} messages`);
    prev = id;
    const shape = checkGameMessageShape(mr.name, mr.payload);
    if (!shape.ok) throw new Error(`${where}: message of player ${id}: ${shape.error}`);
    const error = checkGameMessage(shape.name, shape.payload, kinds);
    if (error !== null) throw new Error(`${where}: message of player ${id}: ${error}`);
    out.push({ playerId: id, name: shape.name, payload: shape.payload });
  }
  return out;
}
