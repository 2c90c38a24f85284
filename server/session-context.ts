// What a client session is given and what it counts: per-client rate and size limits with their defaults, the server
// parts a session uses, and the session's counters. Plain types; client-session.ts and player-inbox.ts act on them.
import type { Clock } from '../shared/clock.ts';
import { MAX_CLIENT_MESSAGE_BYTES } from '../shared/protocol/index.ts';
import type { SessionAccess } from './access/admission.ts';
import type { ClientSession } from './client-session.ts';
import type { Logger } from './logger.ts';
import type { ServerMetrics } from './metrics.ts';
import type { RateLimit } from './rate-limiter.ts';
import type { RoomManager } from './room-manager.ts';

/** Per-client limits. */
export interface SessionLimits {
  /** All messages: sustained rate and burst. Beyond it the client is disconnected (flood). */
  messages: RateLimit;
  /** Input messages alone. */
  inputs: RateLimit;
  /** Refused messages: a few are answered with errors; past this bucket the client is disconnected. */
  badMessages: RateLimit;
  /** Largest accepted frame (bytes). */
  maxMessageBytes: number;
  /** Time allowed between connecting and a valid hello. */
  helloTimeoutMs: number;
  /** Skip snapshots while this many bytes are queued on the socket. */
  snapshotSkipBufferedBytes: number;
  /** Disconnect when this many bytes are queued (reliable messages cannot be dropped, nor queued without bound). */
  maxBufferedBytes: number;
  /** Predict mode: checkpoints a client may ask for (netMode predict, resync); more are refused with rate-limited. */
  resyncs?: RateLimit;
}

/**
 * Defaults: room for 60 inputs + 60 acks + pings per second with slack, and a short leash on garbage. The bursts
 * hold ~10 s of a well-behaved client's traffic: after a network stall (or a server pause) its on-time messages
 * arrive all at once, and that must not read as a flood; the sustained rates still cap a flooder.
 */
export const DEFAULT_SESSION_LIMITS: Readonly<SessionLimits> = Object.freeze({
  messages: { perSecond: 300, burst: 1200 },
  inputs: { perSecond: 150, burst: 600 },
  badMessages: { perSecond: 0.5, burst: 10 },
  maxMessageBytes: MAX_CLIENT_MESSAGE_BYTES,
  helloTimeoutMs: 5_000,
  snapshotSkipBufferedBytes: 256 * 1024,
  maxBufferedBytes: 8 * 1024 * 1024,
});

/** Default limit on checkpoints a client asks for: one a second. */
export const DEFAULT_RESYNC_LIMIT: Readonly<RateLimit> = Object.freeze({ perSecond: 1, burst: 1 });

/** What a session needs from the server. */
export interface SessionContext {
  clock: Clock;
  metrics: ServerMetrics;
  logger: Logger;
  rooms: RoomManager;
  limits: SessionLimits;
  /** Seat and resume rules. */
  access: SessionAccess;
  /** Input delay (ticks) a predict room's welcome announces. */
  inputDelayTicks: number;
  /** Called once when the session ends. */
  onEnd(session: ClientSession): void;
}

/** Counters of one session (tests and logs). */
export interface SessionStats {
  messagesReceived: number;
  badMessages: number;
  errorsSent: number;
  snapshotsSent: number;
  snapshotsSkipped: number;
  snapshotBytes: number;
  bytesSent: number;
  inputsLate: number;
  inputsTooFar: number;
}
