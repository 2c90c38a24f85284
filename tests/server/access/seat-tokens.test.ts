// Tests for server/access/seat-tokens.ts: issue and redeem once, expiry, signature over room/seat/expiry, another
// secret, the room rule, giving a seat back, and forgetting used seats once they expire.
import { describe, expect, it } from 'vitest';
import { SeatTokens } from '../../../server/access/seat-tokens.ts';

const SECRET = 'seat-secret-for-tests-0123';

function make(ttlMs = 60_000): { seats: SeatTokens; wall: { ms: number } } {
  const wall = { ms: 1_700_000_000_000 };
  return { seats: new SeatTokens({ secret: SECRET, nowMs: () => wall.ms, defaultTtlMs: ttlMs }), wall };
}

describe('seat-tokens', () => {
  it('issues a token for a room that is redeemed once, into that room', () => {
    const { seats, wall } = make();
    const seat = seats.issue('arena-1');
    expect(seat).toMatchObject({ roomId: 'arena-1', expiresAtMs: wall.ms + 60_000 });
    expect(seat.token).toMatch(/^s1\.arena-1\.[A-Za-z0-9_-]{22}\.\d+\.[A-Za-z0-9_-]{43}$/);
    expect(seats.redeem(seat.token, null)).toEqual({ ok: true, roomId: 'arena-1', seatId: seat.seatId, expiresAtMs: seat.expiresAtMs });
    expect(seats.redeem(seat.token, null)).toEqual({ ok: false, reason: 'the seat token was already used' });
    expect(seats.issue('arena-1').seatId).not.toBe(seat.seatId);
  });

  it('refuses a token after its expiry, and one for another room than asked', () => {
    const { seats, wall } = make();
    const seat = seats.issue('arena-1', 5000);
    expect(seats.verify(seat.token, 'arena-2')).toEqual({ ok: false, reason: 'the seat token is for room "arena-1", not "arena-2"' });
    wall.ms += 5000;
    expect(seats.verify(seat.token, 'arena-1').ok).toBe(true);
    wall.ms += 1;
    expect(seats.redeem(seat.token, 'arena-1')).toEqual({ ok: false, reason: 'the seat token expired 1 s ago' });
  });

  it('refuses any change to room, seat or expiry, and tokens signed with another secret', () => {
    const { seats, wall } = make();
    const [v, room, id, exp, mac] = seats.issue('arena-1').token.split('.');
    const tampered = [
      [v, 'arena-2', id, exp, mac],
      [v, room, `${id.slice(0, -1)}${id.endsWith('A') ? 'B' : 'A'}`, exp, mac],
      [v, room, id, String(Number(exp) + 3_600_000), mac],
      [v, room, id, exp, `${mac.slice(0, -2)}${mac.endsWith('AA') ? 'BB' : 'AA'}`],
    ];
    for (const parts of tampered) expect(seats.redeem(parts.join('.'), null), parts.join('.')).toMatchObject({ ok: false, reason: expect.stringMatching(/signature is wrong/) });
    const other = new SeatTokens({ secret: 'a-different-secret-987654', nowMs: () => wall.ms });
    expect(seats.redeem(other.issue('arena-1').token, null)).toMatchObject({ ok: false, reason: expect.stringMatching(/signature/) });
    for (const junk of ['', 's1', 's2.arena-1.x.1.y', 's1.arena 1.aaaaaaaaaaaaaaaaaaaaaa.1.' + 'a'.repeat(43), 's1.a.b.c.d.e']) {
      expect(seats.redeem(junk, null).ok, junk).toBe(false);
    }
  });

  it('lets a given-back seat be redeemed again, and forgets used seats once they have expired', () => {
    const { seats, wall } = make();
    const seat = seats.issue('arena-1', 2000);
    expect(seats.redeem(seat.token, null).ok).toBe(true);
    seats.release(seat.seatId);
    expect(seats.redeem(seat.token, null).ok).toBe(true);
    expect(seats.rememberedSeats).toBe(1);
    wall.ms += 5000;
    const next = seats.issue('arena-1');
    expect(seats.redeem(next.token, null).ok).toBe(true);
    expect(seats.rememberedSeats).toBe(1); // the expired one was swept
  });

  it('refuses redemptions while its table of used seats is full, until some of them expire', () => {
    const wall = { ms: 1_000_000 };
    const seats = new SeatTokens({ secret: SECRET, nowMs: () => wall.ms, maxRememberedSeats: 2 });
    expect(seats.redeem(seats.issue('r', 1000).token, null).ok).toBe(true);
    expect(seats.redeem(seats.issue('r', 5000).token, null).ok).toBe(true);
    const waiting = seats.issue('r', 60_000);
    expect(seats.redeem(waiting.token, null)).toEqual({ ok: false, reason: 'too many seats are in use right now; try again shortly' });
    wall.ms += 2000; // the first used seat has expired and can be forgotten
    expect(seats.redeem(waiting.token, null).ok).toBe(true);
    expect(seats.rememberedSeats).toBe(2);
  });

  it('refuses short secrets and lifetimes out of range', () => {
    expect(() => new SeatTokens({ secret: 'short' })).toThrow(/at least 16 characters/);
    expect(() => new SeatTokens({ secret: SECRET, defaultTtlMs: 10 })).toThrow(/between 1 s and 3600 s/);
    const { seats } = make();
    expect(() => seats.issue('arena-1', 3_600_001)).toThrow(/between 1 s and 3600 s/);
    expect(() => seats.issue('bad room')).toThrow(/room id/);
  });
});
