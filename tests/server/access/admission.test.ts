// Tests for server/access/admission.ts through the in-process harness: with seats required a hello needs a valid,
// unused, unexpired seat token for its room; a seat joins the token's room; a failed join gives the seat back; a
// resume token needs no seat; a seat token is checked even when seats are not required.
import { afterEach, describe, expect, it } from 'vitest';
import { SeatTokens } from '../../../server/access/seat-tokens.ts';
import { ByeReason, ErrorCode } from '../../../shared/protocol/index.ts';
import { startHarness, type Harness, type HarnessOptions, type TestClient } from '../harness.ts';
import { emptyScenario, stripScenario } from '../test-scenarios.ts';

let h: Harness | null = null;
afterEach(async () => {
  await h?.close();
  h = null;
});

const SECRET = 'test-join-secret-0123456789';

/** A harness whose seats run on a wall clock the test moves. */
async function seated(over: Partial<HarnessOptions> = {}): Promise<{ h: Harness; seats: SeatTokens; wall: { ms: number } }> {
  const wall = { ms: 1_700_000_000_000 };
  const seats = new SeatTokens({ secret: SECRET, nowMs: () => wall.ms });
  h = await startHarness({ scenarios: [stripScenario, emptyScenario], seats, requireSeat: true, ...over });
  return { h, seats, wall };
}

async function hello(h: Harness, name: string, room: string | null, tokens: { seatToken?: string; resumeToken?: string }): Promise<TestClient> {
  const c = h.connect();
  c.hello(name, room, tokens);
  await h.settle(() => c.welcome !== null || c.closed !== null);
  return c;
}

function refusedWith(c: TestClient, code: string, message: RegExp): void {
  expect(c.welcome).toBeNull();
  expect(c.ofType('error')).toEqual([expect.objectContaining({ code, message: expect.stringMatching(message) })]);
  expect(c.ofType('bye')).toEqual([expect.objectContaining({ reason: ByeReason.SeatRefused })]);
  expect(c.closed?.code).toBe(1008);
}

describe('admission (seats, in-process server)', () => {
  it('refuses a hello without a seat token when seats are required', async () => {
    const { h } = await seated();
    refusedWith(await hello(h, 'ann', null, {}), ErrorCode.SeatRequired, /admits only reserved seats/);
    expect(await h.server.metrics.registry.getSingleMetricAsString('taos_access_refused_total')).toContain('reason="seat-required"} 1');
  });

  it('admits a valid seat into the token\'s room once, and refuses it the second time', async () => {
    const { h, seats } = await seated();
    const seat = seats.issue('test-empty');
    const a = await hello(h, 'ann', null, { seatToken: seat.token });
    expect(a.welcome).toMatchObject({ roomId: 'test-empty', resumed: false });
    refusedWith(await hello(h, 'eve', null, { seatToken: seat.token }), ErrorCode.SeatRefused, /already used/);
    expect(h.room('test-empty').clientCount).toBe(1);
  });

  it('refuses expired, forged, foreign and wrong-room seats, naming the problem', async () => {
    const { h, seats, wall } = await seated();
    const forRoom = seats.issue('default');
    refusedWith(await hello(h, 'a', 'test-empty', { seatToken: forRoom.token }), ErrorCode.SeatRefused, /for room "default", not "test-empty"/);
    const parts = forRoom.token.split('.');
    const otherRoom = [parts[0], 'test-empty', ...parts.slice(2)].join('.');
    refusedWith(await hello(h, 'b', null, { seatToken: otherRoom }), ErrorCode.SeatRefused, /signature is wrong/);
    const foreign = new SeatTokens({ secret: 'another-secret-entirely-42', nowMs: () => wall.ms }).issue('default');
    refusedWith(await hello(h, 'c', null, { seatToken: foreign.token }), ErrorCode.SeatRefused, /signature is wrong/);
    refusedWith(await hello(h, 'd', null, { seatToken: 'not-a-seat-token' }), ErrorCode.SeatRefused, /not a seat token/);
    const soon = seats.issue('default', 5000);
    wall.ms += 6000;
    refusedWith(await hello(h, 'e', null, { seatToken: soon.token }), ErrorCode.SeatRefused, /expired 1 s ago/);
    // None of the refusals used up the seat that was only refused for its room.
    expect((await hello(h, 'f', 'default', { seatToken: forRoom.token })).welcome?.roomId).toBe('default');
  });

  it('gives the seat back when the join it was for fails', async () => {
    const { h, seats } = await seated({ maxClientsPerRoom: 1 });
    const a = await hello(h, 'ann', null, { seatToken: seats.issue('default').token });
    expect(a.welcome).not.toBeNull();
    const seat = seats.issue('default');
    const full = await hello(h, 'bob', null, { seatToken: seat.token });
    expect(full.ofType('error')[0]?.code).toBe(ErrorCode.RoomFull);
    a.send({ type: 'bye' });
    h.ticks(2);
    expect((await hello(h, 'bob', null, { seatToken: seat.token })).welcome).not.toBeNull();
  });

  it('takes a held player back with its resume token alone, without a seat', async () => {
    const { h, seats } = await seated();
    const a = await hello(h, 'ann', null, { seatToken: seats.issue('default').token });
    a.drop();
    h.ticks(5);
    const back = await hello(h, 'ann', null, { resumeToken: a.welcome!.resumeToken! });
    expect(back.welcome).toMatchObject({ playerId: a.welcome!.playerId, resumed: true });
  });

  it('checks a seat token even where seats are not required, and admits hellos without one', async () => {
    const { h, seats } = await seated({ requireSeat: false });
    expect((await hello(h, 'ann', null, {})).welcome).not.toBeNull();
    const seat = seats.issue('default');
    expect((await hello(h, 'bob', null, { seatToken: seat.token })).welcome).not.toBeNull();
    refusedWith(await hello(h, 'eve', null, { seatToken: seat.token }), ErrorCode.SeatRefused, /already used/);
  });
});
