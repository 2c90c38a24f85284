// The checkpoint byte form's optional GAME section: what game-defined input adds to a checkpoint (each player's game
// input values). Written only for scenarios that declare game input, so other checkpoints keep their exact bytes.
import type { ByteReader, ByteWriter } from '../byte-io.ts';
import type { CheckpointData } from './checkpoint.ts';
import type { SimCore } from './sim-core.ts';

/** The section's tag: 'GAME'. */
export const TAG_GAME = 0x454d4147;

/** Whether a checkpoint of this simulation carries a GAME section. */
export function hasGameSection(core: SimCore): boolean {
  return core.gameInputFields.length > 0;
}

/** Writes the section body: per player (in d.players order) the count and values of its game input. */
export function writeGameSection(w: ByteWriter, d: CheckpointData): void {
  w.u32(d.players.length);
  for (const p of d.players) {
    const game = p.input.game ?? [];
    w.u32(game.length);
    for (const v of game) w.i32(v);
  }
}

/** Reads the section body into `players` (the STATE section's list, same order); throws on a mismatch. */
export function readGameSection(r: ByteReader, players: CheckpointData['players'], core: SimCore): void {
  const n = r.u32('game player count');
  if (n !== players.length) throw new Error(`checkpoint: the game section has ${n} players, the state section ${players.length}`);
  for (const p of players) {
    const count = r.u32('game input count');
    if (count !== core.gameInputFields.length) throw new Error(`checkpoint: player ${p.playerId} has ${count} game input values, the scenario declares ${core.gameInputFields.length}`);
    const game: number[] = [];
    for (let i = 0; i < count; i++) game.push(r.i32('game input value'));
    p.input = { ...p.input, game };
  }
  r.expectEnd('game section');
}
