// A fleet of two `serve --redis` processes on a real loopback redis-server: each lists the other's rooms, sends
// players to the server that hosts their room (the SDK client follows), keeps room ids unique across the fleet,
// forgets a killed server within the TTL, and keeps serving its own rooms while Redis is down.
import { afterAll, beforeAll, expect, it } from 'vitest';
import { connect } from '../../../sdk/client.ts';
import { ByeReason, ErrorCode, PROTOCOL_VERSION } from '../../../shared/protocol/index.ts';
import { describeRedis, startRedisServer, type RedisServer } from '../../helpers/redis-server.ts';
import { startServeProcess, type ServeProcess } from '../../helpers/serve-process.ts';
import { WsTestClient } from '../ws-client.ts';

const TTL_SECONDS = 2;

interface ListedRoom {
  id: string;
  scenario: string;
  clients: number;
  server: { id: string; url: string };
}

async function listRooms(server: ServeProcess): Promise<ListedRoom[]> {
  const res = await fetch(`${server.url}api/rooms`);
  expect(res.status).toBe(200);
  return ((await res.json()) as { rooms: ListedRoom[] }).rooms;
}

async function createRoom(server: ServeProcess, body: Record<string, unknown>): Promise<{ status: number; body: Record<string, unknown> }> {
  const res = await fetch(`${server.url}api/rooms`, { method: 'POST', body: JSON.stringify(body) });
  return { status: res.status, body: (await res.json()) as Record<string, unknown> };
}

/** Polls until `pred` holds (bounded); returns how long it took. */
async function eventually(pred: () => Promise<boolean>, timeoutMs: number, what: string): Promise<number> {
  const start = performance.now();
  while (!(await pred())) {
    if (performance.now() - start > timeoutMs) throw new Error(`timed out after ${timeoutMs} ms waiting until ${what}`);
    await new Promise((r) => setTimeout(r, 100));
  }
  return performance.now() - start;
}

describeRedis('a fleet of serve processes on Redis', () => {
  let redis: RedisServer;
  let a: ServeProcess;
  let b: ServeProcess;

  beforeAll(async () => {
    redis = await startRedisServer();
    const fleetArgs = ['--redis', redis.url, '--fleet-ttl', String(TTL_SECONDS), '--log-level', 'warn', '--client-dir', '/nonexistent', '--max-rooms', '16'];
    [a, b] = await Promise.all([startServeProcess(fleetArgs), startServeProcess(fleetArgs)]);
  });

  afterAll(async () => {
    await Promise.all([a?.stop('SIGKILL'), b?.stop('SIGKILL')]);
    await redis?.stop();
  });

  it('lists a room opened through A on B, naming A as its server, and the SDK client joins it through B', async () => {
    const created = await createRoom(a, { scenario: 'character-course' });
    expect(created.status).toBe(201);
    const roomId = (created.body.room as { id: string }).id;
    await eventually(async () => (await listRooms(b)).some((r) => r.id === roomId && r.server.url === a.url), 5000, `B lists room ${roomId} on A`);
    const onB = await listRooms(b);
    // B's own default room comes first and names B; A's default room is A's own and not listed by B.
    expect(onB[0]).toMatchObject({ id: 'default', server: { url: b.url } });
    expect(onB.filter((r) => r.id === 'default')).toHaveLength(1);

    const client = connect(b.wsUrl, { name: 'Ada', room: roomId, reconnect: false });
    const moves: string[] = [];
    client.on('moved', (m) => moves.push(m.url));
    try {
      const welcome = await client.whenConnected();
      expect(welcome.roomId).toBe(roomId);
      expect(moves).toEqual([a.wsUrl]);
      expect(client.url).toBe(a.wsUrl);
      await eventually(async () => (await listRooms(a)).find((r) => r.id === roomId)?.clients === 1, 5000, 'A counts the player');
      // B answers for the players of A's room (a page on B asks it for name tags).
      const players = (await (await fetch(`${b.url}api/rooms/${roomId}/players`)).json()) as { players: Array<{ name: string }> };
      expect(players.players.map((p) => p.name)).toEqual(['Ada']);
    } finally {
      client.close();
    }
  });

  it('answers a hello on B for a room on A with error and bye room-moved carrying A\'s WebSocket URL', async () => {
    const created = await createRoom(a, { scenario: 'character-course', roomId: 'moved-check' });
    expect(created.status).toBe(201);
    const raw = await WsTestClient.connect(b.wsUrl);
    try {
      raw.send({ type: 'hello', version: PROTOCOL_VERSION, name: 'Bo', room: 'moved-check' });
      await raw.waitFor(() => raw.closed !== null, 5000, 'the close');
      expect(raw.ofType('error')).toEqual([{ type: 'error', code: ErrorCode.RoomMoved, message: expect.stringContaining(a.url) }]);
      expect(raw.ofType('bye')).toEqual([{ type: 'bye', reason: ByeReason.RoomMoved, message: expect.stringContaining('moved-check'), url: a.wsUrl }]);
    } finally {
      raw.close();
    }
  });

  it('refuses a room id another server holds with 409 room-moved and its URL, and lets one of two racing creations win', async () => {
    expect((await createRoom(a, { scenario: 'character-course', roomId: 'arena' })).status).toBe(201);
    const clash = await createRoom(b, { scenario: 'character-course', roomId: 'arena' });
    expect(clash).toEqual({ status: 409, body: { error: 'room-moved', message: expect.stringContaining('arena'), roomId: 'arena', url: a.url, wsUrl: a.wsUrl } });
    const seat = await fetch(`${b.url}api/rooms/arena/seats`, { method: 'POST', body: '{}' });
    await eventually(async () => (await listRooms(b)).some((r) => r.id === 'arena'), 5000, 'B lists arena');
    const seatAgain = seat.status === 409 ? seat : await fetch(`${b.url}api/rooms/arena/seats`, { method: 'POST', body: '{}' });
    expect(seatAgain.status).toBe(409);
    expect(await seatAgain.json()).toMatchObject({ error: 'room-moved', url: a.url });

    const race = await Promise.all([createRoom(a, { scenario: 'character-course', roomId: 'duel' }), createRoom(b, { scenario: 'character-course', roomId: 'duel' })]);
    expect(race.map((r) => r.status).sort()).toEqual([201, 409]);
    const loser = race.find((r) => r.status === 409)!;
    const winner = race[0].status === 201 ? a : b;
    expect(loser.body).toMatchObject({ error: 'room-moved', url: winner.url });

    // Ids the servers make up are unique across the fleet too.
    const made = await Promise.all([a, b, a, b].map((s) => createRoom(s, { scenario: 'character-course' })));
    expect(made.map((r) => [r.status, r.body.error])).toEqual([[201, undefined], [201, undefined], [201, undefined], [201, undefined]]);
    const ids = made.map((r) => (r.body.room as { id: string }).id);
    expect(new Set(ids).size).toBe(4);
  });

  it('drops a killed server and its rooms from the listing within the TTL, and frees their ids', async () => {
    expect((await createRoom(a, { scenario: 'character-course', roomId: 'doomed' })).status).toBe(201);
    await eventually(async () => (await listRooms(b)).some((r) => r.id === 'doomed'), 5000, 'B lists doomed');
    await a.stop('SIGKILL');
    // The last heartbeat was at most TTL/3 before the kill, so the record lapses within the TTL; 3 s of slack for
    // B's poll and a loaded machine.
    await eventually(async () => !(await listRooms(b)).some((r) => r.server.url === a.url), TTL_SECONDS * 1000 + 3000, "A's rooms leave B's listing");
    expect((await createRoom(b, { scenario: 'character-course', roomId: 'doomed' })).status).toBe(201);
    expect((await listRooms(b)).find((r) => r.id === 'doomed')?.server.url).toBe(b.url);
  });

  it('keeps serving its own rooms while Redis is down, and refuses new room ids clearly', async () => {
    await redis.stop();
    const rooms = await listRooms(b);
    expect(rooms.some((r) => r.id === 'doomed' && r.server.url === b.url)).toBe(true);
    const client = await WsTestClient.join(b.wsUrl, 'Cy', 'doomed');
    expect(client.welcome?.roomId).toBe('doomed');
    client.close();
    const refused = await createRoom(b, { scenario: 'character-course', roomId: 'offline' });
    expect(refused).toEqual({ status: 503, body: { error: 'server-full', message: expect.stringContaining('fleet directory does not answer') } });
    const health = await fetch(`${b.url}healthz`);
    expect(health.status).toBe(200);
  });
});
