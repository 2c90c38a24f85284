// The wire form of a scenario's game schema inside the welcome's scenario map: its game input fields as
// [name, min, max] rows. Encoders leave the key out when a scenario declares nothing, so built-in welcomes are unchanged.
import { describeValue } from '../sim/describe-value.ts';
import { GAME_NAME_PATTERN, MAX_GAME_INPUT_ABS, MAX_GAME_INPUT_FIELDS, type GameInputField } from '../sim/game-input.ts';

/** The game schema a client learns from the welcome (what the SDK needs to speak the scenario's game API). */
export interface GameSchemaInfo {
  /** Game input fields in name order: the order of InputCommand.game. */
  input?: readonly GameInputField[];
}

/** The welcome's scenario-map entries for `schema` (none for an empty schema). */
export function packGameSchema(schema: GameSchemaInfo): Record<string, unknown> {
  const out: Record<string, unknown> = {};
  if (schema.input && schema.input.length > 0) out.input = schema.input.map((f) => [f.name, f.min, f.max]);
  return out;
}

/** Reads the schema entries of a decoded scenario map; throws an Error naming the field. */
export function unpackGameSchema(scenario: Record<string, unknown>, what: string): GameSchemaInfo {
  const out: GameSchemaInfo = {};
  if (scenario.input !== undefined) out.input = unpackInputFields(scenario.input, `${what}.input`);
  return out;
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
