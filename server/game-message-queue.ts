// A room's game messages waiting for their tick: checked against the scenario's message kinds when offered, at most a
// few per player per tick, and handed to their tick's input record sorted by player (arrival order within one). A
// message is for the room's next tick, or a later one a predicting client named (its own simulation applies it then).
import { checkGameMessage, MAX_GAME_MESSAGES_PER_PLAYER_TICK, type GameMessage, type GameMessageKind } from '../shared/sim/game-messages.ts';

/** The pending game messages of one room. */
export class GameMessageQueue {
  private pending: Array<GameMessage & { tick: number }> = [];

  /** The messages waiting, with their ticks, in arrival order (a room moving to another thread takes them along). */
  waiting(): Array<GameMessage & { tick: number }> {
    return this.pending.map((m) => ({ ...m, payload: [...m.payload] }));
  }

  /** Puts back messages taken with waiting() (before any other is offered). */
  restore(messages: ReadonlyArray<GameMessage & { tick: number }>): void {
    this.pending = messages.map((m) => ({ ...m, payload: [...m.payload] }));
  }

  /** Queues a message for `tick` (at or after the room's next tick); returns why it was refused, or null. */
  offer(playerId: number, name: string, payload: readonly number[], kinds: readonly GameMessageKind[], tick: number): string | null {
    const error = checkGameMessage(name, payload, kinds);
    if (error !== null) return error;
    let mine = 0;
    for (const m of this.pending) if (m.playerId === playerId && m.tick === tick) mine++;
    if (mine >= MAX_GAME_MESSAGES_PER_PLAYER_TICK) return `at most ${MAX_GAME_MESSAGES_PER_PLAYER_TICK} game messages per tick`;
    this.pending.push({ playerId, name, payload: [...payload], tick });
    return null;
  }

  /**
   * Takes the messages of tick `tick` (and any older) from players still in the room (`inRoom`), sorted by player id,
   * arrival order kept; messages of players who left are dropped.
   */
  take(tick: number, inRoom: (playerId: number) => boolean): GameMessage[] {
    if (this.pending.length === 0) return [];
    const out: GameMessage[] = [];
    const later: typeof this.pending = [];
    for (const m of this.pending) {
      if (!inRoom(m.playerId)) continue;
      if (m.tick <= tick) out.push({ playerId: m.playerId, name: m.name, payload: m.payload });
      else later.push(m);
    }
    this.pending = later;
    return out.sort((a, b) => a.playerId - b.playerId); // Array.prototype.sort is stable
  }
}
