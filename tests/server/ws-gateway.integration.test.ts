// Integration tests for server/ws-gateway.ts on loopback: upgrades on the HTTP port, refusals before the upgrade,
// messages that arrive before the owner attaches, oversize frames reported as 1009, and dead peers terminated.
import { createServer, type Server } from 'node:http';
import type { AddressInfo } from 'node:net';
import { afterEach, describe, expect, it } from 'vitest';
import WebSocket from 'ws';
import { SystemClock } from '../../server/clock.ts';
import type { ServerConnection } from '../../server/connection.ts';
import { attachWsGateway, type WsGateway } from '../../server/ws-gateway.ts';

let http: Server | null = null;
let gateway: WsGateway | null = null;
afterEach(async () => {
  await gateway?.close(200);
  if (http) await new Promise<void>((done) => http!.close(() => done()));
  http = null;
  gateway = null;
});

async function listen(opts: { refuse?: () => string | null; heartbeatMs?: number; onConnection: (c: ServerConnection) => void }): Promise<string> {
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

  it('terminates a peer that stops answering pings', async () => {
    const closes: number[] = [];
    const url = await listen({ heartbeatMs: 60, onConnection: (c) => c.attach({ message: () => {}, close: (code) => closes.push(code) }) });
    const alive = new WebSocket(url);
    const dead = new WebSocket(url, { autoPong: false });
    await Promise.all([new Promise((r) => alive.once('open', r)), new Promise((r) => dead.once('open', r))]);
    await waitFor(() => closes.length === 1, 3000);
    expect(closes[0]).toBe(1006);
    expect(dead.readyState).not.toBe(WebSocket.OPEN);
    expect(alive.readyState).toBe(WebSocket.OPEN);
    alive.close();
  });
});
