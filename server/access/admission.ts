// The access settings a client session applies to its hello, and the seat rule: a seat token in a hello is always
// checked and used up; without one, the hello is admitted only when the server does not require seats.
import { ErrorCode } from '../../shared/protocol/opcodes.ts';
import type { ResumeTokens } from './resume-tokens.ts';
import type { SeatTokens } from './seat-tokens.ts';

/** What sessions check a hello against. */
export interface SessionAccess {
  /** Resume tokens and the grace window; null: players leave as soon as their link drops. */
  resume: ResumeTokens | null;
  /** Seat tokens; null: this server issues none (a hello with a seat token is refused). */
  seats: SeatTokens | null;
  /** Whether a hello without a valid seat token is refused (--require-seat). */
  requireSeat: boolean;
}

/** No seats, no resume: every hello joins as a new player and a dropped player leaves at once. */
export const OPEN_ACCESS: Readonly<SessionAccess> = Object.freeze({ resume: null, seats: null, requireSeat: false });

/** The seat decision for a fresh join: the room to join (null: the hello's) and the seat used, or a refusal. */
export type SeatAdmission =
  | { ok: true; roomId: string | null; seatId: string | null }
  | { ok: false; code: typeof ErrorCode.SeatRequired | typeof ErrorCode.SeatRefused; message: string };

/** Checks (and uses up) the hello's seat token. `room` is the hello's room (null: the token's room). */
export function admitSeat(access: SessionAccess, seatToken: string | undefined, room: string | null): SeatAdmission {
  if (seatToken === undefined) {
    if (!access.requireSeat) return { ok: true, roomId: room, seatId: null };
    return { ok: false, code: ErrorCode.SeatRequired, message: 'this server admits only reserved seats: the hello needs a seat token (POST /api/rooms/:id/seats)' };
  }
  if (access.seats === null) return { ok: false, code: ErrorCode.SeatRefused, message: 'this server does not issue seat tokens' };
  const seat = access.seats.redeem(seatToken, room);
  if (!seat.ok) return { ok: false, code: ErrorCode.SeatRefused, message: seat.reason };
  return { ok: true, roomId: seat.roomId, seatId: seat.seatId };
}
