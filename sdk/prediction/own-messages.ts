// The predicting client's own game messages until the server confirms them: each is applied on the next predicted tick
// at once (the message asks the server for that tick; one arriving after the server ran it gets a later tick), and
// taken out when a confirmed record carries it. One the server has not applied by its predicted tick moves to a later
// one; one never confirmed (the server refused it) is dropped after a while. No timers, no sockets.
import { MAX_GAME_MESSAGES_PER_PLAYER_TICK, type GameMessage } from '../../shared/sim/game-messages.ts';

interface Pending {
  name: string;
  payload: readonly number[];
  /** The predicted tick it is applied on; null until a tick at or after `minTick` is predicted. */
  tick: number | null;
  minTick: number;
  /** The first tick it was predicted on (null: not yet). */
  firstTick: number | null;
}

/** The own messages a Predictor applies ahead of the server. */
export class OwnMessages {
  private readonly pending: Pending[] = [];
  private readonly playerId: number;
  /** Confirmed ticks after its first predicted tick before a message that never appears is dropped. */
  private readonly giveUpTicks: number;

  constructor(playerId: number, giveUpTicks: number) {
    this.playerId = playerId;
    this.giveUpTicks = giveUpTicks;
  }

  /** Messages sent and not yet confirmed. */
  get size(): number {
    return this.pending.length;
  }

  /** A message just sent: it goes on the first predicted tick at or after `presentTick`. */
  add(name: string, payload: readonly number[], presentTick: number): void {
    this.pending.push({ name, payload: [...payload], tick: null, minTick: presentTick, firstTick: null });
  }

  /** The own messages of predicted tick `tick` (assigning waiting ones, at most 8 a tick), in send order. */
  forTick(tick: number): GameMessage[] {
    const out: GameMessage[] = [];
    for (const m of this.pending) {
      if (m.tick === null && m.minTick <= tick && out.length < MAX_GAME_MESSAGES_PER_PLAYER_TICK) {
        m.tick = tick;
        m.firstTick ??= tick;
      }
      if (m.tick === tick) out.push({ playerId: this.playerId, name: m.name, payload: [...m.payload] });
    }
    return out;
  }

  /**
   * Tick `tick` is confirmed with `messages`: the own ones among them are the oldest pending (the server keeps a
   * player's order); pending ones predicted on or before it move to a later tick, or are dropped when long overdue.
   */
  confirmed(tick: number, messages: readonly GameMessage[] | undefined): void {
    let own = 0;
    for (const m of messages ?? []) if (m.playerId === this.playerId) own++;
    this.pending.splice(0, Math.min(own, this.pending.length));
    for (let i = this.pending.length - 1; i >= 0; i--) {
      const m = this.pending[i];
      if (m.tick === null || m.tick > tick) continue;
      if (m.firstTick !== null && tick - m.firstTick > this.giveUpTicks) this.pending.splice(i, 1);
      else {
        m.tick = null;
        m.minTick = tick + 1;
      }
    }
  }

  /** Forgets every pending message (a resync: the new checkpoint says nothing of them). */
  clear(): void {
    this.pending.length = 0;
  }
}
