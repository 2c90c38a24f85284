// Game messages: the named, tick-stamped player actions a scenario declares (pick a team, ready up), each with a
// small bounded integer payload. The host stamps them into a tick's input record, so they are recorded and replayed
// like commands. Declarations, the generic check of a message and the check against a scenario's declaration.
import { describeValue } from './describe-value.ts';
import { GAME_NAME_PATTERN, MAX_GAME_INPUT_ABS } from './game-input.ts';

/** Most message kinds a scenario may declare. */
export const MAX_GAME_MESSAGE_KINDS = 32;
/** Most payload fields of one message. */
export const MAX_GAME_MESSAGE_FIELDS = 8;
/** Most game messages one player may have in one tick's record. */
export const MAX_GAME_MESSAGES_PER_PLAYER_TICK = 8;

/** One declared message: its payload fields by name, each an integer range. */
export interface GameMessageSpec {
  payload?: Readonly<Record<string, { min: number; max: number }>>;
}

/** A resolved message kind: its name and payload fields in name order. */
export interface GameMessageKind {
  readonly name: string;
  readonly fields: readonly { readonly name: string; readonly min: number; readonly max: number }[];
}

/** A game message in a tick's input record: who sent it, which kind, and the payload in field order. */
export interface GameMessage {
  playerId: number;
  name: string;
  payload: readonly number[];
}

/** A message as the scenario's onMessage hook sees it: the payload by field name. */
export interface GameMessageEvent {
  readonly playerId: number;
  readonly name: string;
  readonly payload: Readonly<Record<string, number>>;
}

const bounded = (v: unknown): v is number => typeof v === 'number' && Number.isInteger(v) && Math.abs(v) <= MAX_GAME_INPUT_ABS;

/** Checks a scenario's `messages` declaration; returns the kinds sorted by name. Throws a clear Error. */
export function resolveGameMessageKinds(spec: unknown, scenario: string): readonly GameMessageKind[] {
  if (spec === undefined) return [];
  if (spec === null || typeof spec !== 'object' || Array.isArray(spec)) throw new Error(`scenario ${scenario}: messages must be an object {name: {payload?}}`);
  const names = Object.keys(spec).sort();
  if (names.length > MAX_GAME_MESSAGE_KINDS) throw new Error(`scenario ${scenario}: at most ${MAX_GAME_MESSAGE_KINDS} message kinds, got ${names.length}`);
  return names.map((name) => {
    const where = `scenario ${scenario}: message ${describeValue(name)}`;
    if (!GAME_NAME_PATTERN.test(name)) throw new Error(`${where}: names must be identifiers of 1-32 characters`);
    const m = (spec as Record<string, unknown>)[name] as Record<string, unknown> | null;
    if (m === null || typeof m !== 'object') throw new Error(`${where}: must be {payload?: {field: {min, max}}}`);
    const payload = (m.payload ?? {}) as Record<string, unknown>;
    if (payload === null || typeof payload !== 'object' || Array.isArray(payload)) throw new Error(`${where}: payload must be an object {field: {min, max}}`);
    const fieldNames = Object.keys(payload).sort();
    if (fieldNames.length > MAX_GAME_MESSAGE_FIELDS) throw new Error(`${where}: at most ${MAX_GAME_MESSAGE_FIELDS} payload fields, got ${fieldNames.length}`);
    const fields = fieldNames.map((f) => {
      const r = payload[f] as Record<string, unknown> | null;
      if (!GAME_NAME_PATTERN.test(f)) throw new Error(`${where}: payload field ${describeValue(f)}: names must be identifiers of 1-32 characters`);
      if (r === null || typeof r !== 'object' || !bounded(r.min) || !bounded(r.max) || r.min > r.max) {
        throw new Error(`${where}: payload field ${f} needs integer min ≤ max within ±${MAX_GAME_INPUT_ABS}`);
      }
      return Object.freeze({ name: f, min: r.min + 0, max: r.max + 0 });
    });
    return Object.freeze({ name, fields: Object.freeze(fields) });
  });
}

/** Generic check of an untrusted message (any scenario): name, payload of at most 8 integers. Never throws. */
export function checkGameMessageShape(name: unknown, payload: unknown): { ok: true; name: string; payload: number[] } | { ok: false; error: string } {
  if (typeof name !== 'string' || !GAME_NAME_PATTERN.test(name)) return { ok: false, error: `name must be an identifier of 1-32 characters, got ${describeValue(name)}` };
  if (!Array.isArray(payload) || payload.length > MAX_GAME_MESSAGE_FIELDS) return { ok: false, error: `payload must be an array of at most ${MAX_GAME_MESSAGE_FIELDS} integers` };
  const out: number[] = [];
  for (let i = 0; i < payload.length; i++) {
    const v: unknown = payload[i];
    if (!bounded(v)) return { ok: false, error: `payload[${i}] must be an integer within ±${MAX_GAME_INPUT_ABS}, got ${describeValue(v)}` };
    out.push(v + 0);
  }
  return { ok: true, name, payload: out };
}

/** Checks a message against the scenario's kinds: a declared name, one value per payload field, each in range. */
export function checkGameMessage(name: string, payload: readonly number[], kinds: readonly GameMessageKind[]): string | null {
  const kind = kinds.find((k) => k.name === name);
  if (kind === undefined) return `unknown message ${describeValue(name)} (declared: ${kinds.map((k) => k.name).join(', ') || '(none)'})`;
  if (payload.length !== kind.fields.length) return `message ${name} needs ${kind.fields.length} payload value(s) (${kind.fields.map((f) => f.name).join(', ')}), got ${payload.length}`;
  for (let i = 0; i < payload.length; i++) {
    const f = kind.fields[i];
    if (payload[i] < f.min || payload[i] > f.max) return `message ${name}: ${f.name} must be in [${f.min}, ${f.max}], got ${payload[i]}`;
  }
  return null;
}

/** Named payload values → the field-ordered payload of a declared kind; throws a clear Error. */
export function gameMessagePayload(name: string, values: Readonly<Record<string, number>>, kinds: readonly GameMessageKind[]): number[] {
  const kind = kinds.find((k) => k.name === name);
  if (kind === undefined) throw new Error(`unknown message ${describeValue(name)} (declared: ${kinds.map((k) => k.name).join(', ') || '(none)'})`);
  for (const key of Object.keys(values)) {
    if (!kind.fields.some((f) => f.name === key)) throw new Error(`message ${name} has no payload field ${describeValue(key)} (declared: ${kind.fields.map((f) => f.name).join(', ') || '(none)'})`);
  }
  const payload = kind.fields.map((f) => (Object.hasOwn(values, f.name) ? values[f.name] : 0));
  const error = checkGameMessage(name, payload, kinds) ?? (payload.every((v) => Number.isInteger(v)) ? null : `message ${name}: payload values must be integers`);
  if (error !== null) throw new Error(error);
  return payload;
}

/** The field-ordered payload → values by field name. */
export function gameMessageEvent(msg: GameMessage, kinds: readonly GameMessageKind[]): GameMessageEvent {
  const kind = kinds.find((k) => k.name === msg.name);
  const payload: Record<string, number> = {};
  kind?.fields.forEach((f, i) => (payload[f.name] = msg.payload[i]));
  return Object.freeze({ playerId: msg.playerId, name: msg.name, payload: Object.freeze(payload) });
}
