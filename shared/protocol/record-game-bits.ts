// The game-API parts of a predict-mode record's bits (record-delta.ts): a command's game input values as per-field
// changes, and the tick's game messages (player index, kind index, payload offsets from each range's low end).
// Written only for scenarios that declare game input or messages, so every other scenario's records are unchanged.
// Readers are total over hostile bits: anything out of the declared ranges gives a clear Error.
import type { GameInputField } from '../sim/game-input.ts';
import { MAX_GAME_MESSAGES_PER_PLAYER_TICK, type GameMessage, type GameMessageKind } from '../sim/game-messages.ts';
import type { BitReader, BitWriter } from './bit-stream.ts';

/** What a scenario declares of the game API, as both ends of a record stream need it (fields and kinds name-sorted). */
export interface RecordGameLayout {
  readonly fields: readonly GameInputField[];
  readonly kinds: readonly GameMessageKind[];
}

/** The layout of a scenario without game input or messages. */
export const NO_GAME_LAYOUT: RecordGameLayout = Object.freeze({ fields: [], kinds: [] });

/** A command's game values in canonical record form: one per field (absent ones 0), or undefined when none declared. */
export function canonicalGame(game: readonly number[] | undefined, fields: readonly GameInputField[]): number[] | undefined {
  if (fields.length === 0) return undefined;
  return fields.map((_, i) => game?.[i] ?? 0);
}

/** Whether two canonical game value arrays differ. */
export function gameDiffers(a: readonly number[] | undefined, b: readonly number[] | undefined): boolean {
  if (a === b) return false;
  const x = a ?? [];
  const y = b ?? [];
  return x.length !== y.length || x.some((v, i) => v !== y[i]);
}

/** Writes the changes from `last` to `next` (same length): one bit per field, then the change of the changed ones. */
export function writeGameValues(w: BitWriter, last: readonly number[], next: readonly number[]): void {
  for (let i = 0; i < next.length; i++) {
    const delta = next[i] - last[i];
    w.writeBool(delta !== 0);
    if (delta !== 0) w.writeSignedExpGolomb(delta, 0);
  }
}

/** Reads the values writeGameValues wrote after `last`; at least one must change and all stay in their ranges. */
export function readGameValues(r: BitReader, last: readonly number[], fields: readonly GameInputField[], where: string): number[] {
  let changed = false;
  const out = fields.map((f, i) => {
    if (!r.readBool()) return last[i];
    const delta = r.readSignedExpGolomb(0);
    const value = last[i] + delta;
    if (delta === 0) throw new Error(`${where}: game input ${f.name} marked changed without a change`);
    if (value < f.min || value > f.max) throw new Error(`${where}: game input ${f.name} is ${value}, outside [${f.min}, ${f.max}]`);
    changed = true;
    return value;
  });
  if (!changed) throw new Error(`${where}: game input marked changed with no field`);
  return out;
}

function kindBits(kinds: readonly GameMessageKind[]): number {
  let bits = 0;
  while (1 << bits < kinds.length) bits++;
  return bits;
}

/** Writes a valid record's messages (sorted by player; every sender in `presentIds`, ascending). */
export function writeGameMessages(w: BitWriter, messages: readonly GameMessage[], presentIds: readonly number[], kinds: readonly GameMessageKind[], tick: number): void {
  const where = `RecordDeltaCoder.encode: tick ${tick}`;
  const bits = kindBits(kinds);
  w.writeExpGolomb(messages.length, 0);
  let lastIndex = 0;
  for (const m of messages) {
    const index = presentIds.indexOf(m.playerId);
    if (index < lastIndex) throw new Error(`${where}: a message from player ${m.playerId}, who is not in the game or out of order`);
    const k = kinds.findIndex((kind) => kind.name === m.name);
    if (k < 0) throw new Error(`${where}: message ${m.name} is not declared`);
    const fields = kinds[k].fields;
    if (m.payload.length !== fields.length) throw new Error(`${where}: message ${m.name} needs ${fields.length} payload values`);
    w.writeExpGolomb(index - lastIndex, 0);
    lastIndex = index;
    if (bits > 0) w.writeBits(k, bits);
    fields.forEach((f, i) => w.writeExpGolomb(m.payload[i] - f.min, 0));
  }
}

/** Reads the messages writeGameMessages wrote; senders among `presentIds`, at most 8 per player, payloads in range. */
export function readGameMessages(r: BitReader, presentIds: readonly number[], kinds: readonly GameMessageKind[], tick: number): GameMessage[] {
  const where = `record of tick ${tick}`;
  const bits = kindBits(kinds);
  const count = r.readExpGolomb(0);
  if (count > presentIds.length * MAX_GAME_MESSAGES_PER_PLAYER_TICK) throw new Error(`${where}: ${count} game messages from ${presentIds.length} players`);
  const out: GameMessage[] = [];
  let index = 0;
  let run = 0;
  for (let i = 0; i < count; i++) {
    const step = r.readExpGolomb(0);
    if (step >= presentIds.length - index) throw new Error(`${where}: game message ${i} names no player in the game`);
    index += step;
    run = i > 0 && step === 0 ? run + 1 : 1;
    if (run > MAX_GAME_MESSAGES_PER_PLAYER_TICK) throw new Error(`${where}: player ${presentIds[index]} has more than ${MAX_GAME_MESSAGES_PER_PLAYER_TICK} game messages`);
    const k = bits > 0 ? r.readBits(bits) : 0;
    if (k >= kinds.length) throw new Error(`${where}: game message ${i} has kind ${k}, but ${kinds.length} are declared`);
    const kind = kinds[k];
    const payload = kind.fields.map((f) => {
      const offset = r.readExpGolomb(0);
      if (offset > f.max - f.min) throw new Error(`${where}: message ${kind.name}: ${f.name} is ${f.min + offset}, outside [${f.min}, ${f.max}]`);
      return f.min + offset;
    });
    out.push({ playerId: presentIds[index], name: kind.name, payload });
  }
  return out;
}
