// Integration tests for server/tcp-gate.ts on loopback: an address in back-off is held, answered 429 with Retry-After
// and closed before any HTTP parsing (cut at once past the tarpit's cap); other addresses, and everyone behind a
// trusted proxy, reach the HTTP server.
import { createServer, type Server as HttpServer } from 'node:http';
import { connect, type AddressInfo, type Server } from 'node:net';
import { afterEach, describe, expect, it } from 'vitest';
import { SystemClock } from '../../server/clock.ts';
import { ConnectionPolicy } from '../../server/connection-policy.ts';
import { createMetrics } from '../../server/metrics.ts';
import { createTcpGate, Tarpit } from '../../server/tcp-gate.ts';

let gate: Server | null = null;
let http: HttpServer | null = null;
afterEach(async () => {
  http?.closeAllConnections();
  if (gate) await new Promise<void>((done) => gate!.close(() => done()));
  gate = null;
  http = null;
});

/** A policy in which 127.0.0.1 was kicked three times (refused for 60 s). */
function punishedPolicy(): ConnectionPolicy {
  const policy = new ConnectionPolicy(new SystemClock(), { backoffBaseMs: 60_000 });
  for (let i = 0; i < 3; i++) {
    const t = policy.open('127.0.0.1');
    t.kicked();
    t.closed();
  }
  return policy;
}

async function listen(policy: ConnectionPolicy, trustProxy = false): Promise<{ port: number; requests: number[]; refused: () => Promise<number> }> {
  const requests: number[] = [];
  http = createServer((_req, res) => {
    requests.push(1);
    res.end('ok');
  });
  const metrics = createMetrics({ processMetrics: false });
  gate = createTcpGate(http, { policy, tarpit: new Tarpit(new SystemClock(), { holdMs: 200, maxPerAddress: 2 }), trustProxy, metrics });
  await new Promise<void>((done) => gate!.listen(0, '127.0.0.1', () => done()));
  http.emit('listening');
  const refused = async (): Promise<number> => (await metrics.connectionsRefused.get()).values.reduce((n, v) => n + v.value, 0);
  return { port: (gate.address() as AddressInfo).port, requests, refused };
}

/** Sends a GET from `localAddress`; resolves with what came back and how long the connection lasted. */
function get(port: number, localAddress: string): Promise<{ response: string; ms: number }> {
  return new Promise((resolve) => {
    const started = performance.now();
    const socket = connect({ host: '127.0.0.1', port, localAddress });
    let response = '';
    socket.on('connect', () => socket.write('GET /x HTTP/1.1\r\nHost: t\r\nConnection: close\r\n\r\n'));
    socket.on('data', (d: Buffer) => (response += d.toString('latin1')));
    socket.on('error', () => undefined);
    socket.on('close', () => resolve({ response, ms: performance.now() - started }));
  });
}

describe('tcp-gate', () => {
  it('holds an address in back-off, answers it 429 with Retry-After, and lets another address through', async () => {
    const { port, requests, refused } = await listen(punishedPolicy());
    const held = await get(port, '127.0.0.1');
    expect(held.response).toMatch(/^HTTP\/1\.1 429 Too Many Requests\r\n/);
    expect(held.response).toMatch(/\r\nRetry-After: 60\r\n/);
    expect(held.response).toMatch(/"error":"rate-limited"/);
    expect(held.ms).toBeGreaterThanOrEqual(150);
    expect(requests).toEqual([]);
    expect((await get(port, '127.0.0.2')).response).toMatch(/^HTTP\/1\.1 200 OK/);
    expect(requests).toEqual([1]);
    expect(await refused()).toBe(1);
  });

  it('cuts connections past the tarpit cap at once, without an answer', async () => {
    const { port } = await listen(punishedPolicy());
    const results = await Promise.all([0, 1, 2, 3].map(() => get(port, '127.0.0.1')));
    const answered = results.filter((r) => r.response.startsWith('HTTP/1.1 429'));
    const cut = results.filter((r) => r.response === '');
    expect(answered.length).toBe(2);
    expect(cut.length).toBe(2);
    expect(Math.max(...cut.map((r) => r.ms))).toBeLessThan(Math.min(...answered.map((r) => r.ms)));
  });

  it('lets everything through behind a trusted proxy (the connection is the proxy\'s)', async () => {
    const { port, requests } = await listen(punishedPolicy(), true);
    expect((await get(port, '127.0.0.1')).response).toMatch(/^HTTP\/1\.1 200 OK/);
    expect(requests).toEqual([1]);
  });
});
