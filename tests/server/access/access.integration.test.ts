// Integration tests of access control on a real server (loopback, port 0): the Origin check on WebSocket upgrades
// (403 before any upgrade) and on mutating HTTP requests, the admin token on operator routes, and seats reserved
// over HTTP admitting exactly one hello when the server requires them.
import { request } from 'node:http';
import { mkdtempSync, rmSync } from 'node:fs';
import { tmpdir } from 'node:os';
import { join } from 'node:path';
import WebSocket from 'ws';
import { afterAll, afterEach, describe, expect, it } from 'vitest';
import { silentLogger } from '../../../server/logger.ts';
import { createMetrics } from '../../../server/metrics.ts';
import { startServer, type RunningServer, type StartServerOptions } from '../../../server/start-server.ts';
import { ByeReason, ErrorCode, PROTOCOL_VERSION } from '../../../shared/protocol/index.ts';
import { scenarioList } from '../harness.ts';
import { emptyScenario, stripScenario } from '../test-scenarios.ts';
import { WsTestClient } from '../ws-client.ts';

const tmp = mkdtempSync(join(tmpdir(), 'taos-access-'));
afterAll(() => rmSync(tmp, { recursive: true, force: true }));
let server: RunningServer | null = null;
afterEach(async () => {
  await server?.close('test over');
  server = null;
});

const TOKEN = 'integration-admin-token-0123456789';
const bearer = { authorization: `Bearer ${TOKEN}` };

async function start(extra: Partial<StartServerOptions> = {}): Promise<RunningServer> {
  server = await startServer({
    port: 0,
    scenarios: scenarioList([stripScenario, emptyScenario]),
    scenario: 'test-strip',
    logger: silentLogger(),
    metrics: createMetrics({ processMetrics: false }),
    clientDir: join(tmp, 'no-client'),
    ...extra,
  });
  return server;
}

/** A raw WebSocket upgrade request; resolves with the HTTP answer when the server refuses to switch protocols. */
function upgrade(s: RunningServer, origin: string): Promise<{ status: number; body: string } | 'upgraded'> {
  return new Promise((resolve, reject) => {
    const req = request({
      host: '127.0.0.1',
      port: s.port,
      path: '/',
      headers: { Connection: 'Upgrade', Upgrade: 'websocket', 'Sec-WebSocket-Version': '13', 'Sec-WebSocket-Key': 'dGhlIHNhbXBsZSBub25jZQ==', Origin: origin },
    });
    req.on('upgrade', (_res, socket) => {
      socket.destroy();
      resolve('upgraded');
    });
    req.on('response', (res) => {
      let body = '';
      res.setEncoding('utf8');
      res.on('data', (c: string) => (body += c));
      res.on('end', () => resolve({ status: res.statusCode ?? 0, body }));
    });
    req.on('error', reject);
    req.end();
  });
}

/** Opens a `ws` socket sending this Origin; resolves once it is open. */
function openWithOrigin(url: string, origin: string): Promise<WebSocket> {
  return new Promise((resolve, reject) => {
    const ws = new WebSocket(url, { origin });
    ws.once('open', () => resolve(ws));
    ws.once('error', reject);
  });
}

async function helloWith(s: RunningServer, seatToken?: string): Promise<WsTestClient> {
  const c = await WsTestClient.connect(s.wsUrl);
  c.send({ type: 'hello', version: PROTOCOL_VERSION, name: 'seated', room: null, seatToken });
  await c.waitFor(() => c.welcome !== null || c.closed !== null, 5000, 'welcome or close');
  return c;
}

describe('access control (real sockets)', () => {
  it('answers a WebSocket upgrade from a foreign page with 403 before upgrading, and upgrades loopback, own-address and programs', async () => {
    const s = await start();
    const refused = await upgrade(s, 'https://evil.example');
    expect(refused).toEqual({ status: 403, body: expect.any(String) });
    expect(JSON.parse((refused as { body: string }).body)).toEqual({ error: 'origin-not-allowed', message: expect.stringMatching(/"https:\/\/evil.example" is not allowed/) });
    expect(await upgrade(s, `http://localhost:5173`)).toBe('upgraded');
    for (const origin of ['http://localhost:3000', `http://127.0.0.1:${s.port}`]) {
      const ws = await openWithOrigin(s.wsUrl, origin);
      ws.close();
    }
    const program = await WsTestClient.join(s.wsUrl, 'bot'); // no Origin at all
    expect(program.welcome).not.toBeNull();
    program.close();
    expect(await (await fetch(`${s.url}metrics`)).text()).toContain('taos_access_refused_total{reason="origin-not-allowed"} 1');
  });

  it('refuses mutating requests from foreign pages: a text/plain POST with their Origin, and a cross-site one without', async () => {
    const s = await start();
    const body = JSON.stringify({ scenario: 'test-empty' });
    const foreign = await fetch(`${s.url}api/rooms`, { method: 'POST', body, headers: { origin: 'https://evil.example', 'content-type': 'text/plain' } });
    expect(foreign.status).toBe(403);
    expect(await foreign.json()).toMatchObject({ error: 'origin-not-allowed' });
    const crossSite = await fetch(`${s.url}api/rooms`, { method: 'POST', body, headers: { 'sec-fetch-site': 'cross-site', 'content-type': 'text/plain' } });
    expect(crossSite.status).toBe(403);
    expect(await crossSite.json()).toEqual({ error: 'cross-site-request', message: 'a cross-site browser request without an Origin header is refused' });
    expect(((await (await fetch(`${s.url}api/rooms`, { headers: { origin: 'https://evil.example' } })).json()) as { rooms: unknown[] }).rooms).toHaveLength(1);
    const local = await fetch(`${s.url}api/rooms`, { method: 'POST', body, headers: { origin: 'http://localhost:3000' } });
    expect(local.status).toBe(201);
  });

  it('allows exactly the listed origins when --allowed-origins is given', async () => {
    const s = await start({ allowedOrigins: 'https://game.example' });
    expect(await upgrade(s, 'https://game.example')).toBe('upgraded');
    expect(await upgrade(s, 'http://localhost:3000')).toMatchObject({ status: 403 });
  });

  it('guards operator routes with the admin token: 401 with a challenge, 403 for a wrong one; reads stay open', async () => {
    const s = await start({ adminToken: TOKEN });
    const post = (headers: Record<string, string>) => fetch(`${s.url}api/rooms`, { method: 'POST', body: JSON.stringify({ scenario: 'test-empty' }), headers });
    const none = await post({});
    expect(none.status).toBe(401);
    expect(none.headers.get('www-authenticate')).toBe('Bearer realm="taos-physics"');
    expect(await none.json()).toMatchObject({ error: 'admin-token-required' });
    const wrong = await post({ authorization: 'Bearer not-the-token-at-all' });
    expect(wrong.status).toBe(403);
    expect(await wrong.json()).toMatchObject({ error: 'admin-token-wrong' });
    expect((await post(bearer)).status).toBe(201);
    expect((await fetch(`${s.url}api/rooms/default`, { method: 'DELETE' })).status).toBe(401);
    expect((await fetch(`${s.url}api/rooms/default/seats`, { method: 'POST' })).status).toBe(401);
    expect((await fetch(`${s.url}metrics`)).status).toBe(401);
    const metrics = await fetch(`${s.url}metrics`, { headers: bearer });
    expect(metrics.status).toBe(200);
    const text = await metrics.text();
    expect(text).toContain('taos_access_refused_total{reason="admin-token-required"} 4');
    expect(text).toContain('taos_access_refused_total{reason="admin-token-wrong"} 1');
    expect((await fetch(`${s.url}api/rooms`)).status).toBe(200);
    expect((await fetch(`${s.url}healthz`)).status).toBe(200);
  });

  it('reserves seats over HTTP and, with seats required, admits exactly one hello per seat', async () => {
    const s = await start({ adminToken: TOKEN, requireSeat: true, joinSecret: 'integration-join-secret-42' });
    const reserve = (room: string, body?: string) => fetch(`${s.url}api/rooms/${room}/seats`, { method: 'POST', headers: bearer, body });
    const res = await reserve('default');
    expect(res.status).toBe(201);
    const { seat } = (await res.json()) as { seat: { token: string; roomId: string; seatId: string; expiresAt: string } };
    expect(seat).toMatchObject({ roomId: 'default', token: expect.stringMatching(/^s1\.default\./) });
    const lifetimeMs = Date.parse(seat.expiresAt) - Date.now();
    expect(lifetimeMs).toBeGreaterThan(50_000);
    expect(lifetimeMs).toBeLessThanOrEqual(60_000);
    const short = (await (await reserve('default', '{"ttlSeconds": 5}')).json()) as { seat: { expiresAt: string } };
    expect(Date.parse(short.seat.expiresAt) - Date.now()).toBeLessThanOrEqual(5000);
    const missing = await reserve('nowhere');
    expect(missing.status).toBe(404);
    expect(await missing.json()).toMatchObject({ error: ErrorCode.RoomNotFound });
    expect((await reserve('default', '{"ttlSeconds": 0}')).status).toBe(400);

    const unseated = await helloWith(s);
    expect(unseated.ofType('error')[0]?.code).toBe(ErrorCode.SeatRequired);
    expect(unseated.ofType('bye')[0]?.reason).toBe(ByeReason.SeatRefused);
    const seated = await helloWith(s, seat.token);
    expect(seated.welcome?.roomId).toBe('default');
    const twice = await helloWith(s, seat.token);
    expect(twice.ofType('error')[0]).toMatchObject({ code: ErrorCode.SeatRefused, message: 'the seat token was already used' });
    seated.close();
  });
});
