// Integration tests for server/http-server.ts on a loopback port: routing, status codes for refused requests,
// request-body limits, and that a failing handler answers 500 instead of taking the server down.
import type { Server } from 'node:http';
import type { AddressInfo } from 'node:net';
import { afterEach, describe, expect, it } from 'vitest';
import { createHttpServer, type HttpApi } from '../../server/http-server.ts';
import { RoomError, type RoomInfo } from '../../server/room.ts';
import { ErrorCode } from '../../shared/protocol/index.ts';

let server: Server | null = null;
afterEach(async () => {
  if (server) await new Promise<void>((done) => server!.close(() => done()));
  server = null;
});

const room: RoomInfo = { id: 'default', scenario: 's', clients: 1, tick: 42, bodies: 7, params: {} };

async function serve(over: Partial<HttpApi> = {}): Promise<string> {
  const api: HttpApi = {
    health: () => ({ ok: true, rooms: 1 }),
    listRooms: () => [room],
    listScenarios: () => [{ name: 's' }],
    createRoom: async (req) => {
      if (req.scenario === 'full') throw new RoomError(ErrorCode.ServerFull, 'the server already runs its limit of 6 rooms');
      return { ...room, id: req.roomId ?? 'new-1', scenario: req.scenario };
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
  server = createHttpServer(api);
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

  it('creates rooms by POST and maps refusals to status codes with the reason', async () => {
    const base = await serve();
    const ok = await fetch(`${base}/api/rooms`, { method: 'POST', body: JSON.stringify({ scenario: 's', roomId: 'mine', params: { k: 2 } }) });
    expect(ok.status).toBe(201);
    expect(((await ok.json()) as { room: RoomInfo }).room.id).toBe('mine');
    const full = await fetch(`${base}/api/rooms`, { method: 'POST', body: JSON.stringify({ scenario: 'full' }) });
    expect(full.status).toBe(503);
    expect(await full.json()).toEqual({ error: 'the server already runs its limit of 6 rooms', code: ErrorCode.ServerFull });
    for (const body of ['not json', '[]', '{"scenario": 3}', '{"scenario": "s", "params": {"k": "x"}}', '{"scenario": "s", "roomId": 5}']) {
      const r = await fetch(`${base}/api/rooms`, { method: 'POST', body });
      expect(r.status, body).toBe(400);
      expect(((await r.json()) as { error: string }).error.length).toBeGreaterThan(5);
    }
    const big = await fetch(`${base}/api/rooms`, { method: 'POST', body: JSON.stringify({ scenario: 's', pad: 'x'.repeat(10_000) }) });
    expect(big.status).toBe(413);
    expect(((await big.json()) as { error: string }).error).toMatch(/over 4096 bytes/);
  });

  it('answers unknown methods with 405 and a failing handler with 500, and keeps serving', async () => {
    const base = await serve({
      listRooms: () => {
        throw new Error('boom');
      },
    });
    expect((await fetch(`${base}/api/rooms`, { method: 'DELETE' })).status).toBe(405);
    expect((await fetch(`${base}/healthz`, { method: 'POST' })).status).toBe(405);
    expect((await fetch(`${base}/`, { method: 'PUT' })).status).toBe(405);
    const failed = await fetch(`${base}/api/rooms`);
    expect(failed.status).toBe(500);
    expect(await failed.json()).toEqual({ error: 'internal error', code: 'internal' });
    expect((await fetch(`${base}/healthz`)).status).toBe(200);
  });
});
