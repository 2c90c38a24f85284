// The checkpoint byte form's optional GAME section: what the game API adds to a checkpoint (each player's game input
// values, the game state). Written only for scenarios that declare either, so other checkpoints keep their exact bytes.
import type { ByteReader, ByteWriter } from '../byte-io.ts';
import type { CheckpointData } from './checkpoint.ts';
import type { GameStateValue } from './game-state.ts';
import type { SimCore } from './sim-core.ts';

/** The section's tag: 'GAME'. */
export const TAG_GAME = 0x454d4147;

/** Whether a checkpoint of this simulation carries a GAME section. */
export function hasGameSection(core: SimCore): boolean {
  return core.gameInputFields.length > 0 || core.gameState.fields.length > 0;
}

const NUMBER = 0;
const STRING = 1;

/** Writes the section body: per player (in d.players order) the count and values of its game input. */
export function writeGameSection(w: ByteWriter, d: CheckpointData): void {
  w.u32(d.players.length);
  for (const p of d.players) {
    const game = p.input.game ?? [];
    w.u32(game.length);
    for (const v of game) w.i32(v);
  }
  w.u32(d.gameState.length);
  for (const v of d.gameState) {
    if (typeof v === 'number') w.u8(NUMBER).f64(v);
    else w.u8(STRING).u32PrefixedString(v);
  }
}

/** Reads the section body into `players` (the STATE section's list, same order) and returns the game state values. */
export function readGameSection(r: ByteReader, players: CheckpointData['players'], core: SimCore): GameStateValue[] {
  const np = r.u32('game player count');
  if (np !== players.length) throw new Error(`checkpoint: the game section has ${np} players, the state section ${players.length}`);
  for (const p of players) {
    const count = r.u32('game input count');
    if (count !== core.gameInputFields.length) throw new Error(`checkpoint: player ${p.playerId} has ${count} game input values, the scenario declares ${core.gameInputFields.length}`);
    const game: number[] = [];
    for (let i = 0; i < count; i++) game.push(r.i32('game input value'));
    p.input = { ...p.input, game };
  }
  const n = r.u32('game state count');
  if (n !== core.gameState.fields.length) throw new Error(`checkpoint: ${n} game state values, the scenario declares ${core.gameState.fields.length}`);
  const values: GameStateValue[] = [];
  for (let i = 0; i < n; i++) {
    const kind = r.u8('game state kind');
    if (kind === NUMBER) values.push(r.f64('game state number'));
    else if (kind === STRING) values.push(r.u32PrefixedString('game state string'));
    else throw new Error(`checkpoint: unknown game state kind ${kind}`);
  }
  r.expectEnd('game section');
  return values;
}
