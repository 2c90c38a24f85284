// Integration tests of the network client over real loopback WebSockets (Node 24's global WebSocket) against the
// real server on port 0: two clients join, one walks and the other sees it move in interpolated snapshots, leaving
// removes the character, a shutdown bye and an unreachable server end the client cleanly. Every wait is bounded.
import { afterEach, describe, expect, it } from 'vitest';
import { connect, type NetClient, type NetClientOptions } from '../../sdk/client.ts';
import { silentLogger } from '../../server/logger.ts';
import { createMetrics } from '../../server/metrics.ts';
import { startServer, type RunningServer } from '../../server/start-server.ts';
import { NEUTRAL_INPUT } from '../../shared/sim/input.ts';
import type { ScenarioDefinition } from '../../shared/sim/scenario.ts';
import type { SimEvent } from '../../shared/sim/types.ts';

/** Ground, a few boxes, players side by side. */
const plain: ScenarioDefinition = {
  name: 'net-plain',
  description: 'Ground and boxes for client tests.',
  params: {},
  bounds: { min: { x: -20, y: -5, z: -20 }, max: { x: 20, y: 20, z: 20 } },
  golden: { ticks: 60, bots: 1 },
  build(ctx) {
    ctx.spawn({ kind: 'box', halfExtents: { x: 18, y: 0.5, z: 18 } }, { x: 0, y: -0.5, z: 0 }, null, { motion: 'static', name: 'ground' });
    for (let i = 0; i < 3; i++) ctx.spawn({ kind: 'box', halfExtents: { x: 0.3, y: 0.3, z: 0.3 } }, { x: 6, y: 0.4 + i * 0.7, z: 6 }, null, { motion: 'dynamic' });
    return { spawnPoint: (n) => ({ x: -4 + 3 * (n % 4), y: 0.05, z: 0 }) };
  },
};

let server: RunningServer | null = null;
const clients: NetClient[] = [];
afterEach(async () => {
  for (const c of clients.splice(0)) c.close();
  await server?.close('test over');
  server = null;
});

async function start(): Promise<RunningServer> {
  server = await startServer({
    port: 0,
    scenarios: { get: (n) => (n === plain.name ? plain : undefined), names: () => [plain.name] },
    scenario: plain.name,
    snapshotRateHz: 30,
    logger: silentLogger(),
    metrics: createMetrics({ processMetrics: false }),
    clientDir: '/nonexistent-client-dir',
  });
  return server;
}

async function waitFor(what: string, cond: () => boolean, timeoutMs = 5000): Promise<void> {
  const end = performance.now() + timeoutMs;
  while (!cond()) {
    if (performance.now() > end) throw new Error(`timed out after ${timeoutMs} ms waiting for ${what}`);
    await new Promise((r) => setTimeout(r, 10));
  }
}

function open(url: string, name: string, extra: Partial<NetClientOptions> = {}): NetClient {
  const c = connect(url, { name, ...extra });
  clients.push(c);
  return c;
}

describe('client (real sockets)', () => {
  it('runs on the platform WebSocket of this runtime', () => {
    expect(typeof (globalThis as { WebSocket?: unknown }).WebSocket).toBe('function');
  });

  it('lets two players see each other move and leave', async () => {
    const s = await start();
    const a = open(s.wsUrl, 'Ada');
    const b = open(s.wsUrl, 'Bob');
    const [wa, wb] = await Promise.all([a.whenConnected(), b.whenConnected()]);
    expect(wa.roomId).toBe(wb.roomId);
    expect(wb.staticBodies.length).toBeGreaterThanOrEqual(1);
    const events: SimEvent[] = [];
    b.on('events', (e) => events.push(...e));
    let deltas = 0;
    b.on('snapshot', (snap) => {
      if (snap.baselineTick !== null) deltas++;
    });
    const aOf = () => b.sample().view?.characters.find((c) => c.playerId === wa.playerId);
    await waitFor('B to see A', () => aOf() !== undefined);
    const before = aOf()!.position;
    a.setInput({ ...NEUTRAL_INPUT, moveX: 127 });
    await waitFor('A to move 1 m in B\'s view', () => Math.hypot(aOf()!.position.x - before.x, aOf()!.position.z - before.z) > 1);
    expect(deltas).toBeGreaterThan(5);
    const stats = b.stats();
    expect(stats.rttMs).not.toBeNull();
    expect(Math.abs(stats.serverTick! - b.sample().renderTick)).toBeLessThan(30);
    a.close();
    await waitFor('A to disappear from B\'s view', () => aOf() === undefined);
    expect(events.some((e) => e.type === 'playerLeft' && e.playerId === wa.playerId)).toBe(true);
  });

  it('reports a shutdown bye and ends with its reason without reconnecting', async () => {
    const s = await start();
    const c = open(s.wsUrl, 'Cy', { reconnect: { maxAttempts: 3, baseDelayMs: 50, maxDelayMs: 50 } });
    await c.whenConnected();
    const byes: string[] = [];
    c.on('bye', (bye) => byes.push(bye.reason));
    await s.close('maintenance');
    server = null;
    await waitFor('the client to give up', () => c.state === 'closed');
    expect(byes).toEqual(['server-shutdown']);
    expect(c.closed).toEqual({ reason: 'server-shutdown', detail: 'server-shutdown: maintenance' });
    expect(c.stats().reconnects).toBe(0);
  });

  it('fails cleanly when nothing listens on the port', async () => {
    const s = await start();
    const url = s.wsUrl;
    await s.close('gone');
    server = null;
    const c = open(url, 'Dee', { reconnect: false });
    await expect(c.whenConnected()).rejects.toThrow(/client closed: disconnected/);
    expect(c.closed?.detail).toMatch(/1006/);
  });
});
