// A room's game messages waiting for the next tick: checked against the scenario's message kinds when offered, at
// most a few per player per tick, and handed to the next tick's input record sorted by player (arrival order within one).
import { checkGameMessage, MAX_GAME_MESSAGES_PER_PLAYER_TICK, type GameMessage, type GameMessageKind } from '../shared/sim/game-messages.ts';

/** The pending game messages of one room. */
export class GameMessageQueue {
  private pending: GameMessage[] = [];

  /** The messages waiting, in arrival order (a room moving to another thread takes them along). */
  waiting(): GameMessage[] {
    return this.pending.map((m) => ({ ...m, payload: [...m.payload] }));
  }

  /** Puts back messages taken with waiting() (before any other is offered). */
  restore(messages: readonly GameMessage[]): void {
    this.pending = messages.map((m) => ({ ...m, payload: [...m.payload] }));
  }

  /** Queues a message for the next tick; returns why it was refused, or null. */
  offer(playerId: number, name: string, payload: readonly number[], kinds: readonly GameMessageKind[]): string | null {
    const error = checkGameMessage(name, payload, kinds);
    if (error !== null) return error;
    let mine = 0;
    for (const m of this.pending) if (m.playerId === playerId) mine++;
    if (mine >= MAX_GAME_MESSAGES_PER_PLAYER_TICK) return `at most ${MAX_GAME_MESSAGES_PER_PLAYER_TICK} game messages per tick`;
    this.pending.push({ playerId, name, payload: [...payload] });
    return null;
  }

  /** Takes every pending message of players still in the room (`inRoom`), sorted by player id, arrival order kept. */
  take(inRoom: (playerId: number) => boolean): GameMessage[] {
    if (this.pending.length === 0) return [];
    const out = this.pending.filter((m) => inRoom(m.playerId));
    this.pending = [];
    return out.sort((a, b) => a.playerId - b.playerId); // Array.prototype.sort is stable
  }
}
