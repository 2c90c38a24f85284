// What a joined player's messages do to its seat: inputs (rate-limited, fitted to the room's game input fields,
// offered tick by tick), snapshot acks, game messages and net-mode requests, and the pong a ping gets. It never sends
// or closes anything itself: it says what the session must do (refuse the message, or end the session for a flood).
import type { Clock } from '../shared/clock.ts';
import { ErrorCode, NetMode, type GameMessageMessage, type InputMessage, type PongMessage } from '../shared/protocol/index.ts';
import { checkGameMessage } from '../shared/sim/game-messages.ts';
import { fitInputMessage } from './game-input-gate.ts';
import type { Seat } from './hosted-room.ts';
import type { ServerMetrics } from './metrics.ts';
import type { LinkStats } from './monitor/link-stats.ts';
import { RateLimiter } from './rate-limiter.ts';
import { DEFAULT_RESYNC_LIMIT, type SessionLimits, type SessionStats } from './session-context.ts';

/** What the session does about a message: nothing more (null), refuse it with an error, or end the session (flood). */
export type InboxVerdict = null | { refuse: ErrorCode; message: string } | { flood: string };

/** The session's parts an inbox works with. */
export interface InboxContext {
  clock: Clock;
  metrics: ServerMetrics;
  limits: SessionLimits;
  stats: SessionStats;
  link: LinkStats;
}

/** The pong for a ping: the room's clock and pace as this thread sees them (zeros before the player has a seat). */
export function pongFor(seat: Seat | null, clock: Clock, clientTimeMs: number): PongMessage {
  const pace = seat ? seat.pace() : null;
  return {
    type: 'pong',
    clientTimeMs,
    serverTick: seat ? seat.serverTick() : 0,
    serverTimeMs: clock.nowMs(),
    missedInputTicks: seat ? seat.missedInputTicks() : 0,
    roomTicksPerSecond: pace ? Math.round(pace.ticksPerSecond) : 0,
    roomSlow: pace ? pace.slow : false,
  };
}

/** One joined player's incoming messages, applied to its seat. */
export class PlayerInbox {
  readonly seat: Seat;
  private readonly ctx: InboxContext;
  // Full buckets from the welcome on: nothing before it could spend them (inputs and resyncs are refused until then).
  private readonly inputLimiter: RateLimiter;
  private readonly resyncLimiter: RateLimiter;
  /** How this client is served: snapshots until a predicting client asks for predict mode. */
  private delivery: NetMode = NetMode.Snapshot;

  constructor(seat: Seat, ctx: InboxContext) {
    this.seat = seat;
    this.ctx = ctx;
    this.inputLimiter = new RateLimiter(ctx.clock, ctx.limits.inputs);
    this.resyncLimiter = new RateLimiter(ctx.clock, ctx.limits.resyncs ?? DEFAULT_RESYNC_LIMIT);
  }

  /** Takes the ack an input message carries, then offers each of its commands for its tick. */
  input(msg: InputMessage): InboxVerdict {
    const { seat, ctx } = this;
    if (!this.inputLimiter.take()) return { flood: `more than ${ctx.limits.inputs.perSecond} input messages per second` };
    // Checked by the decoder like an ack message's tick, and as good on its own: refused commands do not void it.
    if (msg.ackTick !== undefined) this.ack(msg.ackTick);
    const fit = fitInputMessage(msg, seat.welcome.scenario.game?.input ?? []);
    if (!fit.ok) return { refuse: ErrorCode.BadInput, message: fit.error };
    if (fit.clamped > 0) ctx.metrics.inputsClamped.inc(fit.clamped);
    if (fit.commands.length > 0) ctx.link.inputArrived(msg.firstTick + fit.commands.length - 1, seat.serverTick());
    seat.offerInputs(msg.firstTick, fit.commands, ctx.stats);
    return null;
  }

  /** The client decoded the snapshot of `tick`. */
  ack(tick: number): void {
    this.seat.acknowledge(tick);
    this.ctx.link.acked(tick, this.ctx.clock.nowMs());
  }

  /** A game message of a kind the scenario declares, for the room's next tick. */
  game(msg: GameMessageMessage): InboxVerdict {
    const refused = checkGameMessage(msg.name, msg.payload, this.seat.welcome.scenario.game?.messages ?? []) ?? this.seat.offerMessage(msg.name, msg.payload, msg.tick);
    return refused === null ? null : { refuse: ErrorCode.BadMessage, message: `game: ${refused}` };
  }

  /** A fresh checkpoint, for a client served in predict mode. */
  resync(): InboxVerdict {
    if (this.delivery !== NetMode.Predict) return { refuse: ErrorCode.UnexpectedMessage, message: 'resync is for clients served in predict mode' };
    return this.askPredict('resync asked for again too soon: at most one checkpoint per second');
  }

  /** A predicting client asks for predict mode (or falls back to snapshots); only a predict-mode room predicts. */
  netMode(mode: NetMode): InboxVerdict {
    if (mode === this.delivery) return null;
    if (mode === NetMode.Snapshot) {
      this.delivery = mode;
      this.seat.setNetMode(mode);
      return null;
    }
    if (this.seat.welcome.netMode !== NetMode.Predict) return { refuse: ErrorCode.UnexpectedMessage, message: `room ${this.seat.welcome.roomId} serves snapshots only` };
    return this.askPredict('net mode switched back to predict too soon: at most one checkpoint per second');
  }

  /** Predict mode from the next tick, starting with a checkpoint: at most one a second. */
  private askPredict(tooSoon: string): InboxVerdict {
    if (!this.resyncLimiter.take()) return { refuse: ErrorCode.RateLimited, message: tooSoon };
    this.delivery = NetMode.Predict;
    this.seat.setNetMode(NetMode.Predict);
    return null;
  }
}
