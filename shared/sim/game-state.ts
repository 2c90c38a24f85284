// Replicated game state: the named values a scenario publishes (score, timer, phase), their declared, name-sorted
// layout and the store the simulation keeps. Values are numbers or short strings; the store counts its changes so
// the server sends state only when it changed. Pure data, no Jolt.
import { describeValue } from './describe-value.ts';
import { GAME_NAME_PATTERN } from './game-input.ts';

/** Most game state fields a scenario may declare. */
export const MAX_GAME_STATE_FIELDS = 32;
/** Longest string value a field may declare (UTF-16 code units). */
export const MAX_GAME_STATE_STRING_LENGTH = 64;

/** One declared state field: a number (finite) or a string of at most maxLength characters (default 32). */
export type GameStateFieldSpec = { kind: 'number'; initial?: number } | { kind: 'string'; maxLength?: number; initial?: string };

/** A resolved field, in name order: its kind, its initial value and (strings) its longest length. */
export interface GameStateField {
  readonly name: string;
  readonly kind: 'number' | 'string';
  /** Longest string (0 for numbers). */
  readonly maxLength: number;
  readonly initial: number | string;
}

/** One state value. */
export type GameStateValue = number | string;
/** State by field name, as the scenario and the SDK see it. */
export type GameStateValues = Readonly<Record<string, GameStateValue>>;

function checkValue(field: GameStateField, value: unknown, where: string): GameStateValue {
  if (field.kind === 'number') {
    if (typeof value !== 'number' || !Number.isFinite(value)) throw new Error(`${where}: ${field.name} must be a finite number, got ${describeValue(value)}`);
    return value + 0; // −0 becomes 0: the hash, the wire and the client see one zero
  }
  if (typeof value !== 'string') throw new Error(`${where}: ${field.name} must be a string, got ${describeValue(value)}`);
  if (value.length > field.maxLength) throw new Error(`${where}: ${field.name} must be at most ${field.maxLength} characters, got ${value.length}`);
  return value;
}

/** Checks a scenario's `state` declaration and returns its fields sorted by name; throws a clear Error. */
export function resolveGameStateFields(spec: unknown, scenario: string): readonly GameStateField[] {
  if (spec === undefined) return [];
  if (spec === null || typeof spec !== 'object' || Array.isArray(spec)) throw new Error(`scenario ${scenario}: state must be an object {name: {kind, …}}`);
  const names = Object.keys(spec).sort();
  if (names.length > MAX_GAME_STATE_FIELDS) throw new Error(`scenario ${scenario}: at most ${MAX_GAME_STATE_FIELDS} game state fields, got ${names.length}`);
  return names.map((name) => {
    const where = `scenario ${scenario}: state field ${describeValue(name)}`;
    if (!GAME_NAME_PATTERN.test(name)) throw new Error(`${where}: names must be identifiers of 1-32 characters`);
    const f = (spec as Record<string, unknown>)[name] as Record<string, unknown> | null;
    if (f === null || typeof f !== 'object') throw new Error(`${where}: must be {kind: 'number'} or {kind: 'string', maxLength?}`);
    if (f.kind !== 'number' && f.kind !== 'string') throw new Error(`${where}: kind must be 'number' or 'string', got ${describeValue(f.kind)}`);
    let maxLength = 0;
    if (f.kind === 'string') {
      maxLength = f.maxLength === undefined ? 32 : (f.maxLength as number);
      if (!Number.isInteger(maxLength) || maxLength < 1 || maxLength > MAX_GAME_STATE_STRING_LENGTH) {
        throw new Error(`${where}: maxLength must be an integer in [1, ${MAX_GAME_STATE_STRING_LENGTH}], got ${describeValue(f.maxLength)}`);
      }
    }
    const field: GameStateField = { name, kind: f.kind, maxLength, initial: f.kind === 'number' ? 0 : '' };
    const initial = f.initial === undefined ? field.initial : checkValue(field, f.initial, `${where} initial value`);
    return Object.freeze({ ...field, initial });
  });
}

/** The simulation's game state: one value per field, in field order, and a count of changes. */
export class GameStateStore {
  readonly fields: readonly GameStateField[];
  private values: GameStateValue[];
  private changes = 0;

  constructor(fields: readonly GameStateField[]) {
    this.fields = fields;
    this.values = fields.map((f) => f.initial);
  }

  /** Bumped whenever a value changes (and on restore): equal versions mean equal state within one simulation. */
  get version(): number {
    return this.changes;
  }

  /** Sets one field; throws a clear Error for an undeclared name or a value of the wrong kind or length. */
  set(name: string, value: unknown): void {
    const i = this.fields.findIndex((f) => f.name === name);
    if (i < 0) {
      const known = this.fields.map((f) => f.name).join(', ') || '(none)';
      throw new Error(`ctx.setState: unknown state field ${describeValue(name)} (declared: ${known})`);
    }
    const v = checkValue(this.fields[i], value, 'ctx.setState');
    if (this.values[i] === v) return;
    this.values[i] = v;
    this.changes++;
  }

  /** One field's value; throws for an undeclared name. */
  get(name: string): GameStateValue {
    const i = this.fields.findIndex((f) => f.name === name);
    if (i < 0) throw new Error(`ctx.getState: unknown state field ${describeValue(name)}`);
    return this.values[i];
  }

  /** The values in field order (a copy). */
  list(): GameStateValue[] {
    return this.values.slice();
  }

  /** The values by name (a frozen copy). */
  named(): GameStateValues {
    const out: Record<string, GameStateValue> = {};
    this.fields.forEach((f, i) => (out[f.name] = this.values[i]));
    return Object.freeze(out);
  }

  /** Puts back values from list() (checkpoint restore); counts as a change. */
  restore(values: readonly GameStateValue[]): void {
    if (values.length !== this.fields.length) throw new Error(`game state: ${values.length} values restored, ${this.fields.length} fields declared`);
    this.values = this.fields.map((f, i) => checkValue(f, values[i], 'game state restore'));
    this.changes++;
  }
}
