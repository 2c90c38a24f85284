// The wire form of a scenario's game schema inside the welcome's scenario map (game input fields as [name, min, max]
// rows, state fields as [name, kind, maxLength] rows, message kinds as [name, [[field, min, max], …]] rows) and the
// check of a snapshot's game state values. Encoders leave
// a key out when a scenario declares nothing, so built-in welcomes are unchanged.
import { describeValue } from '../sim/describe-value.ts';
import { GAME_NAME_PATTERN, MAX_GAME_INPUT_ABS, MAX_GAME_INPUT_FIELDS, type GameInputField } from '../sim/game-input.ts';
import { MAX_GAME_MESSAGE_FIELDS, MAX_GAME_MESSAGE_KINDS, type GameMessageKind } from '../sim/game-messages.ts';
import { MAX_GAME_STATE_FIELDS, MAX_GAME_STATE_STRING_LENGTH, type GameStateField, type GameStateValue } from '../sim/game-state.ts';

/** The game schema a client learns from the welcome (what the SDK needs to speak the scenario's game API). */
export interface GameSchemaInfo {
  /** Game input fields in name order: the order of InputCommand.game. */
  input?: readonly GameInputField[];
  /** Game state fields in name order: the order of a snapshot's state values. */
  state?: readonly StateFieldInfo[];
  /** Game message kinds in name order, each with its payload fields in name order. */
  messages?: readonly GameMessageKind[];
}

/** A state field as the client learns it (its initial value stays on the server; the first snapshot brings values). */
export type StateFieldInfo = Omit<GameStateField, 'initial'>;

/** The welcome's scenario-map entries for `schema` (none for an empty schema). */
export function packGameSchema(schema: GameSchemaInfo): Record<string, unknown> {
  const out: Record<string, unknown> = {};
  if (schema.input && schema.input.length > 0) out.input = schema.input.map((f) => [f.name, f.min, f.max]);
  if (schema.state && schema.state.length > 0) out.state = schema.state.map((f) => [f.name, f.kind, f.maxLength]);
  if (schema.messages && schema.messages.length > 0) out.messages = schema.messages.map((k) => [k.name, k.fields.map((f) => [f.name, f.min, f.max])]);
  return out;
}

/** Reads the schema entries of a decoded scenario map; throws an Error naming the field. */
export function unpackGameSchema(scenario: Record<string, unknown>, what: string): GameSchemaInfo {
  const out: GameSchemaInfo = {};
  if (scenario.input !== undefined) out.input = unpackInputFields(scenario.input, `${what}.input`);
  if (scenario.state !== undefined) out.state = unpackStateFields(scenario.state, `${what}.state`);
  if (scenario.messages !== undefined) out.messages = unpackMessageKinds(scenario.messages, `${what}.messages`);
  return out;
}

function unpackMessageKinds(raw: unknown, what: string): GameMessageKind[] {
  if (!Array.isArray(raw) || raw.length > MAX_GAME_MESSAGE_KINDS) throw new Error(`${what} must be an array of at most ${MAX_GAME_MESSAGE_KINDS} [name, fields] rows`);
  const kinds: GameMessageKind[] = [];
  raw.forEach((row: unknown, i) => {
    if (!Array.isArray(row) || row.length !== 2 || typeof row[0] !== 'string' || !GAME_NAME_PATTERN.test(row[0]) || !Array.isArray(row[1]) || row[1].length > MAX_GAME_MESSAGE_FIELDS) {
      throw new Error(`${what}[${i}] must be [name, [[field, min, max], …]] with at most ${MAX_GAME_MESSAGE_FIELDS} fields, got ${describeValue(row)}`);
    }
    const name = row[0];
    if (i > 0 && !(name > kinds[i - 1].name)) throw new Error(`${what} must be sorted by name without repeats (at ${describeValue(name)})`);
    const fields = (row[1] as unknown[]).map((f: unknown, k) => {
      const bound = (v: unknown): v is number => typeof v === 'number' && Number.isInteger(v) && Math.abs(v) <= MAX_GAME_INPUT_ABS;
      if (!Array.isArray(f) || f.length !== 3 || typeof f[0] !== 'string' || !GAME_NAME_PATTERN.test(f[0]) || !bound(f[1]) || !bound(f[2]) || f[1] > f[2]) {
        throw new Error(`${what}[${i}] field ${k} must be [name, min, max] with integers min ≤ max, got ${describeValue(f)}`);
      }
      return { name: f[0], min: f[1], max: f[2] };
    });
    for (let k = 1; k < fields.length; k++) if (!(fields[k].name > fields[k - 1].name)) throw new Error(`${what}[${i}] fields must be sorted by name without repeats`);
    kinds.push({ name, fields });
  });
  return kinds;
}

function unpackStateFields(raw: unknown, what: string): StateFieldInfo[] {
  if (!Array.isArray(raw) || raw.length > MAX_GAME_STATE_FIELDS) throw new Error(`${what} must be an array of at most ${MAX_GAME_STATE_FIELDS} [name, kind, maxLength] rows`);
  const fields: StateFieldInfo[] = [];
  raw.forEach((row: unknown, i) => {
    const ok =
      Array.isArray(row) &&
      row.length === 3 &&
      typeof row[0] === 'string' &&
      GAME_NAME_PATTERN.test(row[0]) &&
      ((row[1] === 'number' && row[2] === 0) || (row[1] === 'string' && Number.isInteger(row[2]) && row[2] >= 1 && row[2] <= MAX_GAME_STATE_STRING_LENGTH));
    if (!ok) throw new Error(`${what}[${i}] must be [name, 'number', 0] or [name, 'string', maxLength], got ${describeValue(row)}`);
    const [name, kind, maxLength] = row as [string, 'number' | 'string', number];
    if (i > 0 && !(name > fields[i - 1].name)) throw new Error(`${what} must be sorted by name without repeats (at ${describeValue(name)})`);
    fields.push({ name, kind, maxLength });
  });
  return fields;
}

/** Checks a snapshot's game state values (numbers and strings of at most 64 characters); an error sentence otherwise. */
export function checkGameStateValues(raw: unknown): GameStateValue[] | string {
  if (!Array.isArray(raw) || raw.length > MAX_GAME_STATE_FIELDS) return `must be an array of at most ${MAX_GAME_STATE_FIELDS} values`;
  for (let i = 0; i < raw.length; i++) {
    const v: unknown = raw[i];
    const ok = (typeof v === 'number' && Number.isFinite(v)) || (typeof v === 'string' && v.length <= MAX_GAME_STATE_STRING_LENGTH);
    if (!ok) return `[${i}] must be a finite number or a string of at most ${MAX_GAME_STATE_STRING_LENGTH} characters, got ${describeValue(v)}`;
  }
  return raw as GameStateValue[];
}

function unpackInputFields(raw: unknown, what: string): GameInputField[] {
  if (!Array.isArray(raw) || raw.length > MAX_GAME_INPUT_FIELDS) throw new Error(`${what} must be an array of at most ${MAX_GAME_INPUT_FIELDS} [name, min, max] rows`);
  const fields: GameInputField[] = [];
  raw.forEach((row: unknown, i) => {
    const bound = (v: unknown): v is number => typeof v === 'number' && Number.isInteger(v) && Math.abs(v) <= MAX_GAME_INPUT_ABS;
    if (!Array.isArray(row) || row.length !== 3 || typeof row[0] !== 'string' || !GAME_NAME_PATTERN.test(row[0]) || !bound(row[1]) || !bound(row[2]) || row[1] >= row[2]) {
      throw new Error(`${what}[${i}] must be [name, min, max] with an identifier name and integers min < max, got ${describeValue(row)}`);
    }
    if (i > 0 && !(row[0] > fields[i - 1].name)) throw new Error(`${what} must be sorted by name without repeats (at ${describeValue(row[0])})`);
    fields.push({ name: row[0], min: row[1], max: row[2] });
  });
  return fields;
}
