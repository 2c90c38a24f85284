// Game-defined input: the extra named input fields a scenario declares (bounded integer axes and buttons), their
// resolved, name-sorted layout, and how a command's `game` values are checked against it. Pure data, no Jolt.
import { describeValue } from './describe-value.ts';
import type { InputCommand } from './input.ts';

/** Most game input fields a scenario may declare. */
export const MAX_GAME_INPUT_FIELDS = 16;
/** Largest magnitude of a game input value (and of a declared range's ends). */
export const MAX_GAME_INPUT_ABS = 1_000_000;
/** What a game-defined name looks like: an identifier of 1–32 characters. */
export const GAME_NAME_PATTERN = /^[A-Za-z_][A-Za-z0-9_]{0,31}$/;

/** Names the built-in command already uses (a game field may not shadow them). */
const BUILT_IN_FIELDS = new Set(['moveX', 'moveZ', 'yaw', 'pitch', 'buttons', 'game']);

/** One declared game input field: a button (0 or 1) or an integer axis in [min, max]. */
export type GameInputFieldSpec = { kind: 'button' } | { kind: 'axis'; min: number; max: number };

/** A resolved field: its name and integer range, in the order the wire, the log and the hash use (sorted by name). */
export interface GameInputField {
  readonly name: string;
  readonly min: number;
  readonly max: number;
}

/** Named game input values, as the SDK's setInput and ScenarioContext.gameInput speak them. */
export type GameInputValues = Readonly<Record<string, number>>;

/** Checks a scenario's `input` declaration and returns its fields sorted by name; throws a clear Error. */
export function resolveGameInputFields(spec: unknown, scenario: string): readonly GameInputField[] {
  if (spec === undefined) return [];
  if (spec === null || typeof spec !== 'object' || Array.isArray(spec)) throw new Error(`scenario ${scenario}: input must be an object {name: {kind, …}}`);
  const names = Object.keys(spec).sort();
  if (names.length > MAX_GAME_INPUT_FIELDS) throw new Error(`scenario ${scenario}: at most ${MAX_GAME_INPUT_FIELDS} game input fields, got ${names.length}`);
  return names.map((name) => {
    const where = `scenario ${scenario}: input field ${describeValue(name)}`;
    if (!GAME_NAME_PATTERN.test(name)) throw new Error(`${where}: names must be identifiers of 1-32 characters`);
    if (BUILT_IN_FIELDS.has(name)) throw new Error(`${where}: the name is taken by the built-in command`);
    const f = (spec as Record<string, unknown>)[name] as Record<string, unknown> | null;
    if (f === null || typeof f !== 'object') throw new Error(`${where}: must be {kind: 'button'} or {kind: 'axis', min, max}`);
    if (f.kind === 'button') return Object.freeze({ name, min: 0, max: 1 });
    if (f.kind !== 'axis') throw new Error(`${where}: kind must be 'button' or 'axis', got ${describeValue(f.kind)}`);
    const ok = (v: unknown): v is number => typeof v === 'number' && Number.isInteger(v) && Math.abs(v) <= MAX_GAME_INPUT_ABS;
    if (!ok(f.min) || !ok(f.max) || f.min >= f.max) {
      throw new Error(`${where}: an axis needs integer min < max within ±${MAX_GAME_INPUT_ABS}, got [${describeValue(f.min)}, ${describeValue(f.max)}]`);
    }
    return Object.freeze({ name, min: f.min + 0, max: f.max + 0 });
  });
}

/** The result of fitting a command's game values to a scenario's fields. */
export type GameInputFit = { ok: true; command: InputCommand; clamped: boolean } | { ok: false; error: string };

/**
 * Fits a validated command to a scenario's fields: no `game` values means all zero; otherwise there must be exactly
 * one per field, each clamped into its range. A scenario without fields refuses commands that carry game values.
 */
export function fitGameInput(cmd: InputCommand, fields: readonly GameInputField[]): GameInputFit {
  const given = cmd.game;
  if (fields.length === 0) {
    if (given === undefined || given.length === 0) return { ok: true, command: cmd, clamped: false };
    return { ok: false, error: `game input given (${given.length} values) but the scenario declares no game input fields` };
  }
  if (given === undefined || given.length === 0) return { ok: true, command: { ...cmd, game: fields.map(() => 0) }, clamped: false };
  if (given.length !== fields.length) {
    return { ok: false, error: `game input must have ${fields.length} values (${fields.map((f) => f.name).join(', ')}), got ${given.length}` };
  }
  let clamped = false;
  const game = given.map((v, i) => {
    const f = fields[i];
    if (v < f.min || v > f.max) clamped = true;
    return v < f.min ? f.min : v > f.max ? f.max : v;
  });
  return { ok: true, command: { ...cmd, game }, clamped };
}

/** Named values → the field-ordered array; unknown names and non-numbers throw a clear Error. Missing names are 0. */
export function gameInputArray(values: GameInputValues, fields: readonly GameInputField[]): number[] {
  for (const key of Object.keys(values)) {
    if (!fields.some((f) => f.name === key)) {
      const known = fields.map((f) => f.name).join(', ') || '(none)';
      throw new Error(`unknown game input field ${describeValue(key)} (declared: ${known})`);
    }
  }
  return fields.map((f) => {
    const v = Object.hasOwn(values, f.name) ? values[f.name] : 0;
    if (typeof v !== 'number' || !Number.isFinite(v)) throw new Error(`game input ${f.name} must be a finite number, got ${describeValue(v)}`);
    const r = Math.round(v) + 0;
    return r < f.min ? f.min : r > f.max ? f.max : r;
  });
}

/** The field-ordered array → named values (missing values read as 0). */
export function gameInputValues(game: readonly number[] | undefined, fields: readonly GameInputField[]): GameInputValues {
  const out: Record<string, number> = {};
  fields.forEach((f, i) => (out[f.name] = game?.[i] ?? 0));
  return Object.freeze(out);
}
