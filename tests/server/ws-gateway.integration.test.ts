// Integration tests for server/ws-gateway.ts on loopback: upgrades on the HTTP port, refusals before the upgrade
// (full, per-address caps), messages that arrive before the owner attaches, oversize frames reported as 1009, dead
// peers terminated and counted, a kicked socket cut shortly after its close frame, the messages of one turn
// written to the socket at once, and every byte intact when writes queue behind a client that stopped reading.
import { createServer, type IncomingMessage, type Server } from 'node:http';
import type { AddressInfo } from 'node:net';
import { afterEach, describe, expect, it } from 'vitest';
import WebSocket from 'ws';
import { SystemClock } from '../../server/clock.ts';
import type { ServerConnection } from '../../server/connection.ts';
import { ConnectionPolicy } from '../../server/connection-policy.ts';
import { createMetrics, type ServerMetrics } from '../../server/metrics.ts';
import { attachWsGateway, type WsGateway } from '../../server/ws-gateway.ts';
import { maskedFrame, openRawWs } from './raw-ws.ts';

let http: Server | null = null;
let gateway: WsGateway | null = null;
afterEach(async () => {
  await gateway?.close(200);
  if (http) await new Promise<void>((done) => http!.close(() => done()));
  http = null;
  gateway = null;
});

interface ListenOptions {
  refuse?: () => string | null;
  heartbeatMs?: number;
  closeGraceMs?: number;
  policy?: ConnectionPolicy;
  metrics?: ServerMetrics;
  onConnection: (c: ServerConnection, req: IncomingMessage) => void;
}

async function listen(opts: ListenOptions): Promise<string> {
  http = createServer((_, res) => res.writeHead(404).end());
  gateway = attachWsGateway(http, { clock: new SystemClock(), maxPayloadBytes: 1024, ...opts });
  await new Promise<void>((done) => http!.listen(0, '127.0.0.1', () => done()));
  return `ws://127.0.0.1:${(http.address() as AddressInfo).port}/`;
}

function waitFor(pred: () => boolean, ms = 3000): Promise<void> {
  const start = performance.now();
  return new Promise((resolve, reject) => {
    const poll = (): void => {
      if (pred()) resolve();
      else if (performance.now() - start > ms) reject(new Error('timed out'));
      else setTimeout(poll, 5);
    };
    poll();
  });
}

describe('ws-gateway', () => {
  it('delivers binary messages in order, including those sent before the owner attached', async () => {
    let conn: ServerConnection | null = null;
    const url = await listen({ onConnection: (c) => (conn = c) });
    const ws = new WebSocket(url);
    await new Promise((r) => ws.once('open', r));
    ws.send(Uint8Array.of(1));
    ws.send(Uint8Array.of(2));
    ws.send('text');
    await waitFor(() => conn !== null);
    await new Promise((r) => setTimeout(r, 50));
    const got: Array<[number[], boolean]> = [];
    conn!.attach({ message: (d, binary) => got.push([Array.from(d), binary]), close: () => {} });
    ws.send(Uint8Array.of(3));
    await waitFor(() => got.length === 4);
    expect(got).toEqual([[[1], true], [[2], true], [[116, 101, 120, 116], false], [[3], true]]);
    const echoed: number[][] = [];
    ws.on('message', (d: Buffer) => echoed.push(Array.from(d)));
    conn!.send(Uint8Array.of(9, 9));
    await waitFor(() => echoed.length === 1);
    expect(echoed).toEqual([[9, 9]]);
    ws.close();
  });

  it('writes everything sent to a socket in one turn with one write, and the next turn with another', async () => {
    let conn: ServerConnection | null = null;
    const writes: number[] = [];
    const url = await listen({
      onConnection: (c, req) => {
        conn = c;
        // Count what reaches the TCP socket's own write paths (each is one write or writev system call).
        const raw = req.socket as unknown as { _write: (...a: unknown[]) => void; _writev: (chunks: unknown[], cb: () => void) => void };
        const write = raw._write.bind(raw);
        const writev = raw._writev.bind(raw);
        raw._write = (...a: unknown[]) => {
          writes.push(1);
          write(...a);
        };
        raw._writev = (chunks, cb) => {
          writes.push(chunks.length);
          writev(chunks, cb);
        };
      },
    });
    const ws = new WebSocket(url);
    const got: number[][] = [];
    ws.on('message', (d: Buffer) => got.push(Array.from(d)));
    await new Promise((r) => ws.once('open', r));
    await waitFor(() => conn !== null);
    conn!.attach({ message: () => {}, close: () => {} });
    // A room tick's events, snapshot and one more message for this client, all in one synchronous run.
    conn!.send(Uint8Array.of(1));
    conn!.send(Uint8Array.of(2, 2));
    conn!.send(new Uint8Array(300).fill(3));
    await new Promise((r) => setTimeout(r, 20));
    conn!.send(Uint8Array.of(4));
    await waitFor(() => got.length === 4);
    expect(got.map((m) => m[0])).toEqual([1, 2, 3, 4]);
    expect(got[2]).toHaveLength(300);
    // Two writes of one buffer each: the three messages framed together, then the later one.
    expect(writes).toEqual([1, 1]);
    ws.close();
  });

  it('delivers every byte intact to a client that stops reading while many turns are sent to it and to others', async () => {
    const conns: ServerConnection[] = [];
    const url = await listen({ onConnection: (c) => conns.push(c) });
    const slow = new WebSocket(url);
    const fast = new WebSocket(url);
    const got = new Map<WebSocket, Buffer[]>([[slow, []], [fast, []]]);
    for (const [ws, list] of got) ws.on('message', (d: Buffer) => list.push(d));
    await Promise.all([slow, fast].map((ws) => new Promise((r) => ws.once('open', r))));
    await waitFor(() => conns.length === 2);
    for (const c of conns) c.attach({ message: () => {}, close: () => {} });
    // The slow client stops reading: once the kernel buffers are full (16 MB sent), writes to it queue in its stream.
    const slowSocket = (slow as unknown as { _socket: { pause(): void; resume(): void } })._socket;
    slowSocket.pause();
    const turns = 2000;
    const message = (turn: number, size: number): Buffer => Buffer.from(Uint8Array.from({ length: size }, (_, i) => (turn * 7 + i) & 0xff));
    const sent: Buffer[] = [];
    for (let t = 0; t < turns; t++) {
      sent.push(message(t, 8000), message(t + 1, 100));
      for (const c of conns) {
        c.send(sent[2 * t]);
        c.send(sent[2 * t + 1]);
      }
      await new Promise((r) => setImmediate(r));
    }
    expect(conns.some((c) => c.bufferedAmount() > 0)).toBe(true);
    slowSocket.resume();
    await waitFor(() => got.get(slow)!.length === 2 * turns && got.get(fast)!.length === 2 * turns, 20_000);
    for (const list of got.values()) expect(list.findIndex((m, i) => !m.equals(sent[i]))).toBe(-1);
    slow.close();
    fast.close();
  }, 30_000);

  it('refuses the upgrade with 503 and the reason when told to', async () => {
    const url = await listen({ refuse: () => 'server full (1 connections)', onConnection: () => {} });
    const ws = new WebSocket(url);
    const status = await new Promise<number>((resolve) => ws.once('unexpected-response', (_req, res) => resolve(res.statusCode ?? 0)));
    expect(status).toBe(503);
  });

  it('reports an oversize frame as a 1009 close', async () => {
    const closes: number[] = [];
    const url = await listen({ onConnection: (c) => c.attach({ message: () => {}, close: (code) => closes.push(code) }) });
    const ws = new WebSocket(url);
    await new Promise((r) => ws.once('open', r));
    ws.send(new Uint8Array(5000));
    await waitFor(() => closes.length === 1);
    expect(closes).toEqual([1009]);
  });

  it('terminates a peer that stops answering pings and counts it as a keep-alive disconnect', async () => {
    const closes: number[] = [];
    const metrics = createMetrics({ processMetrics: false });
    const url = await listen({ heartbeatMs: 60, metrics, onConnection: (c) => c.attach({ message: () => {}, close: (code) => closes.push(code) }) });
    const alive = new WebSocket(url);
    const dead = new WebSocket(url, { autoPong: false });
    await Promise.all([new Promise((r) => alive.once('open', r)), new Promise((r) => dead.once('open', r))]);
    await waitFor(() => closes.length === 1, 3000);
    expect(closes[0]).toBe(1006);
    expect(dead.readyState).not.toBe(WebSocket.OPEN);
    expect(alive.readyState).toBe(WebSocket.OPEN);
    expect((await metrics.disconnects.get()).values).toEqual([{ labels: { reason: 'keepalive-timeout' }, value: 1 }]);
    alive.close();
  });

  it('refuses a socket over the per-address half-open cap with 429, Retry-After and the reason, and not other addresses', async () => {
    const metrics = createMetrics({ processMetrics: false });
    const policy = new ConnectionPolicy(new SystemClock(), { maxPendingPerAddress: 1 });
    const url = await listen({ policy, metrics, onConnection: (c) => c.attach({ message: () => {}, close: () => {} }) });
    const first = await openRawWs(url, { localAddress: '127.0.0.1' });
    expect(first.status).toBe(101);
    const second = await openRawWs(url, { localAddress: '127.0.0.1' });
    expect(second.status).toBe(429);
    expect(second.head).toMatch(/\r\nRetry-After: 1\r\n/);
    await waitFor(() => second.closed);
    const other = await openRawWs(url, { localAddress: '127.0.0.2' });
    expect(other.status).toBe(101);
    expect(policy.countsOf('127.0.0.1')).toEqual({ sockets: 1, pending: 1, kicks: 0 });
    expect((await metrics.connectionsRefused.get()).values).toEqual([{ labels: { reason: 'address-pending' }, value: 1 }]);
    first.socket.destroy();
    other.socket.destroy();
    await waitFor(() => policy.openSockets === 0);
  });

  it('stops reading a kicked socket and cuts it after the close grace, counting it until it is gone', async () => {
    const policy = new ConnectionPolicy(new SystemClock());
    let messages = 0;
    const url = await listen({
      policy,
      closeGraceMs: 300,
      onConnection: (c) =>
        c.attach({
          message: () => {
            messages++;
            c.kicked?.('flood');
            c.close(1008, 'flood: go away');
          },
          close: () => {},
        }),
    });
    // A hostile peer: keeps writing after the close frame and never answers it.
    const raw = await openRawWs(url);
    const frame = maskedFrame(new Uint8Array(1000));
    const started = performance.now();
    const flood = setInterval(() => {
      if (!raw.socket.destroyed) raw.socket.write(Buffer.concat(Array.from({ length: 64 }, () => frame)));
    }, 5);
    try {
      await waitFor(() => raw.closed, 5000);
    } finally {
      clearInterval(flood);
    }
    const aliveMs = performance.now() - started;
    expect(messages).toBe(1);
    expect(aliveMs).toBeGreaterThanOrEqual(250);
    expect(aliveMs).toBeLessThan(3000);
    expect(policy.countsOf('127.0.0.1').kicks).toBe(1);
    await waitFor(() => policy.openSockets === 0);
  });
});
