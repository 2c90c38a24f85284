// Seat reservations: short-lived tokens a game backend gets from `POST /api/rooms/:id/seats` and hands to a player,
// signed with HMAC-SHA256 over (room, seat id, expiry) under the join secret. A seat is redeemed once: used seat ids
// are remembered until they expire. Stateless to verify, so any process sharing the secret can check a token.
import { createHmac, randomBytes, timingSafeEqual } from 'node:crypto';
import { ROOM_ID_PATTERN } from '../../shared/protocol/limits.ts';

/** Shortest join secret accepted. */
export const MIN_JOIN_SECRET_LENGTH = 16;
/** Environment variable the serve command reads the join secret from. */
export const JOIN_SECRET_ENV = 'TAOS_JOIN_SECRET';
/** Default lifetime of a seat token. */
export const DEFAULT_SEAT_TTL_MS = 60_000;
/** Longest lifetime a reservation may ask for. */
export const MAX_SEAT_TTL_MS = 3_600_000;

const VERSION = 's1';
const SEAT_ID = /^[A-Za-z0-9_-]{22}$/;
const EXPIRY = /^[0-9]{1,15}$/;
const MAC = /^[A-Za-z0-9_-]{43}$/;
/** Default for the most used seats remembered at once (each until its expiry). */
const MAX_REMEMBERED_SEATS = 100_000;

/** A reserved seat. */
export interface SeatReservation {
  /** The token the player puts in its hello (`seatToken`). */
  token: string;
  roomId: string;
  seatId: string;
  /** Wall-clock time (ms since 1970) after which the token is refused. */
  expiresAtMs: number;
}

/** A checked seat, or why it is refused. */
export type SeatCheck = { ok: true; roomId: string; seatId: string; expiresAtMs: number } | { ok: false; reason: string };

/** Options of SeatTokens. */
export interface SeatTokensOptions {
  /** The join secret (≥ 16 characters); processes that share it accept each other's tokens. */
  secret: string;
  /** Wall clock in ms since 1970 (tokens travel between machines). Default Date.now. */
  nowMs?: () => number;
  /** Lifetime of a token when the reservation does not say. Default 60 s. */
  defaultTtlMs?: number;
  /** Most used seats remembered at once; past it redemptions are refused until some expire. Default 100 000. */
  maxRememberedSeats?: number;
}

/** Issues and redeems seat tokens. */
export class SeatTokens {
  readonly defaultTtlMs: number;
  private readonly secret: Buffer;
  private readonly nowMs: () => number;
  private readonly maxRemembered: number;
  /** Used seat id → its expiry; an entry can go once its token would be refused as expired anyway. */
  private readonly used = new Map<string, number>();
  private lastSweepMs = 0;

  constructor(opts: SeatTokensOptions) {
    if (opts.secret.length < MIN_JOIN_SECRET_LENGTH) throw new Error(`the join secret must be at least ${MIN_JOIN_SECRET_LENGTH} characters (e.g. the output of \`openssl rand -hex 32\`)`);
    this.secret = Buffer.from(opts.secret, 'utf8');
    this.nowMs = opts.nowMs ?? Date.now;
    this.defaultTtlMs = opts.defaultTtlMs ?? DEFAULT_SEAT_TTL_MS;
    this.maxRemembered = opts.maxRememberedSeats ?? MAX_REMEMBERED_SEATS;
    if (!Number.isInteger(this.defaultTtlMs) || this.defaultTtlMs < 1000 || this.defaultTtlMs > MAX_SEAT_TTL_MS) {
      throw new Error(`the seat lifetime must be between 1 s and ${MAX_SEAT_TTL_MS / 1000} s, got ${this.defaultTtlMs} ms`);
    }
  }

  /** Used seats remembered now (each until it expires). */
  get rememberedSeats(): number {
    return this.used.size;
  }

  /** Reserves a seat in `roomId` for `ttlMs` (default defaultTtlMs). Throws for a bad room id or lifetime. */
  issue(roomId: string, ttlMs: number = this.defaultTtlMs): SeatReservation {
    if (!ROOM_ID_PATTERN.test(roomId)) throw new Error(`room id must match ${ROOM_ID_PATTERN}`);
    if (!Number.isInteger(ttlMs) || ttlMs < 1000 || ttlMs > MAX_SEAT_TTL_MS) throw new Error(`a seat lives between 1 s and ${MAX_SEAT_TTL_MS / 1000} s, got ${ttlMs} ms`);
    const seatId = randomBytes(16).toString('base64url');
    const expiresAtMs = Math.floor(this.nowMs()) + ttlMs;
    return { token: `${VERSION}.${roomId}.${seatId}.${expiresAtMs}.${this.mac(roomId, seatId, expiresAtMs)}`, roomId, seatId, expiresAtMs };
  }

  /**
   * Checks a token (signature, expiry, room) without using it. `room` is the room the hello asked for (null: the
   * token's own room).
   */
  verify(token: string, room: string | null): SeatCheck {
    const parts = token.split('.');
    if (parts.length !== 5 || parts[0] !== VERSION) return { ok: false, reason: 'the seat token is not a seat token of this server' };
    const [, roomId, seatId, expiry, mac] = parts;
    if (!ROOM_ID_PATTERN.test(roomId) || !SEAT_ID.test(seatId) || !EXPIRY.test(expiry) || !MAC.test(mac)) return { ok: false, reason: 'the seat token is malformed' };
    const expiresAtMs = Number(expiry);
    const expected = this.mac(roomId, seatId, expiresAtMs);
    if (!timingSafeEqual(Buffer.from(mac, 'base64url'), Buffer.from(expected, 'base64url'))) return { ok: false, reason: 'the seat token signature is wrong (forged, or signed with another join secret)' };
    const now = this.nowMs();
    if (now > expiresAtMs) return { ok: false, reason: `the seat token expired ${Math.ceil((now - expiresAtMs) / 1000)} s ago` };
    if (room !== null && room !== roomId) return { ok: false, reason: `the seat token is for room "${roomId}", not "${room}"` };
    return { ok: true, roomId, seatId, expiresAtMs };
  }

  /** verify() and, when valid and not used before, marks the seat used. */
  redeem(token: string, room: string | null): SeatCheck {
    const check = this.verify(token, room);
    if (!check.ok) return check;
    if (this.used.has(check.seatId)) return { ok: false, reason: 'the seat token was already used' };
    this.sweep();
    if (this.used.size >= this.maxRemembered) return { ok: false, reason: 'too many seats are in use right now; try again shortly' };
    this.used.set(check.seatId, check.expiresAtMs);
    return check;
  }

  /** Gives a redeemed seat back (the join it was for failed), so the token works again until it expires. */
  release(seatId: string): void {
    this.used.delete(seatId);
  }

  private mac(roomId: string, seatId: string, expiresAtMs: number): string {
    return createHmac('sha256', this.secret).update(`taos-seat/1\n${roomId}\n${seatId}\n${expiresAtMs}`).digest('base64url');
  }

  /** Forgets used seats whose tokens have expired (at most once a second, so a full table costs nothing per call). */
  private sweep(): void {
    const now = this.nowMs();
    if (now - this.lastSweepMs < 1000) return;
    this.lastSweepMs = now;
    for (const [id, expiresAtMs] of this.used) if (now > expiresAtMs) this.used.delete(id);
  }
}
