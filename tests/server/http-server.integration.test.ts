// Integration tests for server/http-server.ts on a loopback port: routing, status codes and the one error shape
// {error: code, message} for refused requests, request-body limits, malformed URLs, and that a failing handler
// answers 500 instead of taking the server down.
import type { Server } from 'node:http';
import type { AddressInfo } from 'node:net';
import { afterEach, describe, expect, it } from 'vitest';
import { HttpError } from '../../server/http-errors.ts';
import { createHttpServer, type HttpApi } from '../../server/http-server.ts';
import { RoomError, type RoomInfo } from '../../server/room.ts';
import { ErrorCode } from '../../shared/protocol/index.ts';

let server: Server | null = null;
afterEach(async () => {
  if (server) await new Promise<void>((done) => server!.close(() => done()));
  server = null;
});

const room: RoomInfo = { id: 'default', scenario: 's', clients: 1, tick: 42, bodies: 7, params: {}, netMode: 'snapshot', ticksPerSecond: 60, slow: false, tickMsP99: 0.5, tickCpuMsP99: 0.4, tickGapMsMax: 18 };

async function serve(over: Partial<HttpApi> = {}, onError?: (error: unknown) => void): Promise<string> {
  const api: HttpApi = {
    health: () => ({ ok: true, rooms: 1 }),
    listRooms: () => [room],
    listScenarios: () => [{ name: 's' }],
    createRoom: async (req) => {
      if (req.scenario === 'full') throw new RoomError(ErrorCode.ServerFull, 'the server already runs its limit of 6 rooms');
      return { room: { ...room, id: req.roomId ?? 'new-1', scenario: req.scenario }, created: req.roomId !== 'default' };
    },
    deleteRoom: async (id) => {
      if (id === 'default') throw new HttpError(409, 'default-room', 'the default room stays open while the server runs');
      throw new HttpError(404, 'room-not-found', `no room "${id}"`);
    },
    reserveSeat: (roomId, req) => {
      if (roomId !== room.id) throw new RoomError(ErrorCode.RoomNotFound, `no room "${roomId}" is open`);
      return { token: `s1.${roomId}.seat`, roomId, seatId: 'seat', expiresAt: new Date((req.ttlSeconds ?? 60) * 1000).toISOString() };
    },
    metrics: async () => ({ body: 'taos_x 1\n', contentType: 'text/plain; version=0.0.4' }),
    staticFiles: async (req, res) => {
      if (req.url !== '/' || req.method !== 'GET') return false;
      res.writeHead(200).end('page');
      return true;
    },
    ...over,
  };
  server = createHttpServer(api, onError);
  await new Promise<void>((done) => server!.listen(0, '127.0.0.1', () => done()));
  return `http://127.0.0.1:${(server.address() as AddressInfo).port}`;
}

describe('http-server', () => {
  it('routes health, rooms, one room, scenarios, metrics and static files', async () => {
    const base = await serve();
    expect(await (await fetch(`${base}/healthz`)).json()).toEqual({ ok: true, rooms: 1 });
    expect(await (await fetch(`${base}/api/rooms`)).json()).toEqual({ rooms: [room] });
    expect(await (await fetch(`${base}/api/rooms/default`)).json()).toEqual({ room });
    expect((await fetch(`${base}/api/rooms/missing`)).status).toBe(404);
    expect(await (await fetch(`${base}/api/scenarios`)).json()).toEqual({ scenarios: [{ name: 's' }] });
    const m = await fetch(`${base}/metrics`);
    expect(m.headers.get('content-type')).toMatch(/text\/plain/);
    expect(await m.text()).toBe('taos_x 1\n');
    expect(await (await fetch(`${base}/`)).text()).toBe('page');
  });

  it('creates rooms by POST (201, or 200 for an open one) and maps refusals to status codes with a code', async () => {
    const base = await serve();
    const ok = await fetch(`${base}/api/rooms`, { method: 'POST', body: JSON.stringify({ scenario: 's', roomId: 'mine', params: { k: 2 } }) });
    expect(ok.status).toBe(201);
    expect(((await ok.json()) as { room: RoomInfo }).room.id).toBe('mine');
    expect((await fetch(`${base}/api/rooms`, { method: 'POST', body: JSON.stringify({ scenario: 's', roomId: 'default' }) })).status).toBe(200);
    const full = await fetch(`${base}/api/rooms`, { method: 'POST', body: JSON.stringify({ scenario: 'full' }) });
    expect(full.status).toBe(503);
    expect(await full.json()).toEqual({ error: 'server-full', message: 'the server already runs its limit of 6 rooms' });
    const refused: Array<[string, string]> = [
      ['not json', 'bad-json'],
      ['[]', 'bad-body'],
      ['{"scenario": 3}', 'bad-body'],
      ['{"scenario": "s", "params": {"k": "x"}}', 'bad-param'],
      ['{"scenario": "s", "roomId": 5}', 'bad-body'],
    ];
    for (const [body, code] of refused) {
      const r = await fetch(`${base}/api/rooms`, { method: 'POST', body });
      expect(r.status, body).toBe(400);
      const answer = (await r.json()) as { error: string; message: string };
      expect(answer.error, body).toBe(code);
      expect(answer.message.length, body).toBeGreaterThan(10);
    }
    const big = await fetch(`${base}/api/rooms`, { method: 'POST', body: JSON.stringify({ scenario: 's', pad: 'x'.repeat(10_000) }) });
    expect(big.status).toBe(413);
    expect(await big.json()).toEqual({ error: 'body-too-large', message: 'request body over 4096 bytes' });
  });

  it('refuses an unknown field by name', async () => {
    const base = await serve();
    const r = await fetch(`${base}/api/rooms`, { method: 'POST', body: JSON.stringify({ scenario: 's', id: 'mine' }) });
    expect(r.status).toBe(400);
    expect(await r.json()).toEqual({ error: 'unknown-field', message: 'unknown field "id": POST /api/rooms takes scenario, params, roomId, netMode' });
  });

  it('answers malformed percent-encoding in a room id with 400, not 500', async () => {
    const errors: unknown[] = [];
    const base = await serve({}, (e) => errors.push(e));
    for (const path of ['/api/rooms/%E0%A4%A', '/api/rooms/%', '/api/rooms/%ZZ']) {
      for (const method of ['GET', 'DELETE']) {
        const r = await fetch(`${base}${path}`, { method });
        expect(r.status, `${method} ${path}`).toBe(400);
        expect(((await r.json()) as { error: string }).error).toBe('bad-url');
      }
    }
    expect(errors).toEqual([]);
  });

  it('routes DELETE /api/rooms/:id to the API and answers its refusals', async () => {
    const base = await serve();
    const missing = await fetch(`${base}/api/rooms/nope`, { method: 'DELETE' });
    expect(missing.status).toBe(404);
    expect(await missing.json()).toEqual({ error: 'room-not-found', message: 'no room "nope"' });
    const def = await fetch(`${base}/api/rooms/default`, { method: 'DELETE' });
    expect(def.status).toBe(409);
    expect(((await def.json()) as { error: string }).error).toBe('default-room');
  });

  it('answers unknown methods with 405 and an Allow header, unknown API paths with 404, a failing handler with 500, and keeps serving', async () => {
    const errors: unknown[] = [];
    const base = await serve(
      {
        listRooms: () => {
          throw new Error('boom');
        },
      },
      (e) => errors.push(e),
    );
    const del = await fetch(`${base}/api/rooms`, { method: 'DELETE' });
    expect(del.status).toBe(405);
    expect(del.headers.get('allow')).toBe('GET, HEAD, POST');
    expect(await del.json()).toEqual({ error: 'method-not-allowed', message: 'DELETE /api/rooms is not supported (allowed: GET, HEAD, POST)' });
    expect((await fetch(`${base}/healthz`, { method: 'POST' })).status).toBe(405);
    expect((await fetch(`${base}/api/rooms/default`, { method: 'PUT' })).headers.get('allow')).toBe('GET, HEAD, DELETE');
    expect((await fetch(`${base}/`, { method: 'PUT' })).status).toBe(405);
    const unknown = await fetch(`${base}/api/nothing`);
    expect(unknown.status).toBe(404);
    expect(((await unknown.json()) as { error: string }).error).toBe('not-found');
    const failed = await fetch(`${base}/api/rooms`);
    expect(failed.status).toBe(500);
    expect(await failed.json()).toEqual({ error: 'internal', message: 'internal error' });
    expect(errors).toEqual([new Error('boom')]);
    expect((await fetch(`${base}/healthz`)).status).toBe(200);
  });
});
