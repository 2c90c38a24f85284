// Builds a server's access control from its options (allowed origins, admin token, join secret, seats, resume
// grace), checking them before anything starts: the HTTP guard, the WebSocket upgrade check and the seat tokens.
import { randomBytes } from 'node:crypto';
import type { IncomingMessage } from 'node:http';
import type { Logger } from '../logger.ts';
import type { ServerMetrics } from '../metrics.ts';
import { AdminAuth } from './admin-auth.ts';
import { createHttpGuard } from './http-guard.ts';
import { originFacts, parseAllowedOrigins } from './origin-policy.ts';
import { AccessCode, type Refusal } from './refusal.ts';
import { DEFAULT_SEAT_TTL_MS, SeatTokens } from './seat-tokens.ts';

/** The access options of startServer (the serve command's flags). */
export interface AccessOptions {
  /** Origins whose pages may open a WebSocket or send mutating requests: origins, `self`, `loopback`, `*`. Default self,loopback. */
  allowedOrigins?: string | readonly string[];
  /** Bearer token for POST/DELETE on /api/ and for /metrics; absent or null: those routes need none. */
  adminToken?: string | null;
  /** HMAC key of seat tokens (≥ 16 characters); absent: a random key per process. */
  joinSecret?: string | null;
  /** Admit only hellos with a valid seat token. Needs adminToken. */
  requireSeat?: boolean;
  /** Lifetime of a seat token when the reservation does not say (ms). Default 60 000. */
  seatTtlMs?: number;
  /** Wall clock for seat expiry, ms since 1970 (tests). Default Date.now. */
  wallClockMs?: () => number;
}

/** Access control ready to wire into the HTTP server, the WebSocket gateway and the game server. */
export interface ServerAccess {
  authorize(req: IncomingMessage, method: string, path: string): Refusal | null;
  checkUpgrade(req: IncomingMessage): Refusal | null;
  seats: SeatTokens;
  requireSeat: boolean;
  /** What is in force, for the startup log (no secrets). */
  summary: { allowedOrigins: string; adminToken: boolean; joinSecret: 'given' | 'random per process'; requireSeat: boolean; seatTtlSeconds: number };
}

/** Distinct refused origins logged per process (each once, so a hostile page cannot flood the log). */
const MAX_LOGGED_ORIGINS = 256;

/** Checks the options and builds the guards; throws an Error naming the bad option. */
export function createServerAccess(opts: AccessOptions, metrics: ServerMetrics, logger?: Logger): ServerAccess {
  const origins = parseAllowedOrigins(opts.allowedOrigins);
  const adminToken = opts.adminToken ?? null;
  const admin = adminToken === null ? null : new AdminAuth(adminToken);
  const requireSeat = opts.requireSeat ?? false;
  if (requireSeat && admin === null) throw new Error('--require-seat needs --admin-token: without it anyone could reserve a seat');
  const given = opts.joinSecret ?? null;
  const seats = new SeatTokens({
    secret: given ?? randomBytes(32).toString('base64url'),
    nowMs: opts.wallClockMs,
    defaultTtlMs: opts.seatTtlMs ?? DEFAULT_SEAT_TTL_MS,
  });
  const loggedOrigins = new Set<string>();
  const counted = (refusal: Refusal | null, req: IncomingMessage): Refusal | null => {
    if (refusal === null) return null;
    metrics.accessRefused.inc({ reason: refusal.code });
    const origin = req.headers.origin;
    // An operator whose own page is refused learns why from the log, once per origin.
    if (refusal.code === AccessCode.OriginNotAllowed && typeof origin === 'string' && !loggedOrigins.has(origin) && loggedOrigins.size < MAX_LOGGED_ORIGINS) {
      loggedOrigins.add(origin);
      logger?.warn({ origin: origin.slice(0, 200), allowed: origins.entries.join(',') }, 'refused a page of another origin (add it to --allowed-origins if it is yours)');
    }
    return refusal;
  };
  const guard = createHttpGuard({ origins, admin });
  return {
    authorize: (req, method, path) => counted(guard(req, method, path), req),
    checkUpgrade: (req) => counted(origins.check(originFacts(req)), req),
    seats,
    requireSeat,
    summary: {
      allowedOrigins: origins.entries.join(','),
      adminToken: admin !== null,
      joinSecret: given === null ? 'random per process' : 'given',
      requireSeat,
      seatTtlSeconds: seats.defaultTtlMs / 1000,
    },
  };
}

/** A warning for the startup log when a server reachable from other machines leaves operator routes open. */
export function openAdminWarning(host: string, access: ServerAccess): string | null {
  const loopbackOnly = host === 'localhost' || host.startsWith('127.') || host === '::1';
  if (access.summary.adminToken || loopbackOnly) return null;
  return `listening on ${host} without --admin-token: anyone who can reach the port can create rooms, reserve seats and read /metrics`;
}

/** The logger call for the access summary. */
export function logAccess(logger: Logger, host: string, access: ServerAccess): void {
  logger.info(access.summary, 'access control');
  const warning = openAdminWarning(host, access);
  if (warning !== null) logger.warn({ host }, warning);
}
