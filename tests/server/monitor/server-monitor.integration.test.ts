// Integration test of the monitor over a real server on loopback: /monitor/state and /monitor/events list a room and
// its players (admin token required when set), the kick and close actions end the players' clients with those
// reasons, and /metrics carries per-room labels. Every wait is bounded.
import { afterEach, describe, expect, it } from 'vitest';
import { connect, type NetClient } from '../../../sdk/client.ts';
import { silentLogger } from '../../../server/logger.ts';
import { createMetrics } from '../../../server/metrics.ts';
import type { MonitorState } from '../../../server/monitor/server-monitor.ts';
import { startServer, type RunningServer } from '../../../server/start-server.ts';
import { NEUTRAL_INPUT } from '../../../shared/sim/input.ts';
import type { ScenarioDefinition } from '../../../shared/sim/scenario.ts';

const arena: ScenarioDefinition = {
  name: 'monitor-arena',
  description: 'Ground and a box for monitor tests.',
  params: { boxes: { default: 1, min: 0, max: 4, description: 'boxes', integer: true } },
  bounds: { min: { x: -20, y: -5, z: -20 }, max: { x: 20, y: 20, z: 20 } },
  golden: { ticks: 60, bots: 1 },
  build(ctx) {
    ctx.spawn({ kind: 'box', halfExtents: { x: 18, y: 0.5, z: 18 } }, { x: 0, y: -0.5, z: 0 }, null, { motion: 'static', name: 'ground' });
    for (let i = 0; i < ctx.params.boxes; i++) ctx.spawn({ kind: 'box', halfExtents: { x: 0.3, y: 0.3, z: 0.3 } }, { x: 6, y: 0.4 + i, z: 6 }, null, { motion: 'dynamic' });
    return { spawnPoint: (n) => ({ x: -4 + 3 * (n % 4), y: 0.05, z: 0 }) };
  },
};
const TOKEN = 'monitor-test-token-0123456789';

let server: RunningServer | null = null;
const clients: NetClient[] = [];
afterEach(async () => {
  for (const c of clients.splice(0)) c.close();
  await server?.close('test over');
  server = null;
});

async function waitFor(what: string, cond: () => boolean | Promise<boolean>, timeoutMs = 8000): Promise<void> {
  const end = performance.now() + timeoutMs;
  while (!(await cond())) {
    if (performance.now() > end) throw new Error(`timed out after ${timeoutMs} ms waiting for ${what}`);
    await new Promise((r) => setTimeout(r, 20));
  }
}

const auth = { authorization: `Bearer ${TOKEN}` };

async function state(url: string): Promise<MonitorState> {
  const res = await fetch(new URL('/monitor/state', url), { headers: auth });
  expect(res.status).toBe(200);
  return (await res.json()) as MonitorState;
}

describe('server monitor', () => {
  it('lists a room and its players live, kicks one, closes the room, and labels /metrics per room', async () => {
    server = await startServer({
      port: 0,
      scenarios: { get: (n) => (n === arena.name ? arena : undefined), names: () => [arena.name] },
      scenario: arena.name,
      logger: silentLogger(),
      metrics: createMetrics({ processMetrics: false }),
      clientDir: '/nonexistent-client-dir',
      adminToken: TOKEN,
    });
    const url = server.url;
    // Without the token the data is refused; the page itself is served.
    expect((await fetch(new URL('/monitor/state', url))).status).toBe(401);
    expect((await fetch(new URL('/monitor/events', url))).status).toBe(401);
    const page = await fetch(new URL('/monitor', url));
    expect(page.status).toBe(200);
    expect(await page.text()).toMatch(/<title>taos-physics monitor<\/title>/);

    const created = await fetch(new URL('/api/rooms', url), { method: 'POST', headers: { ...auth, 'content-type': 'application/json' }, body: JSON.stringify({ scenario: arena.name, roomId: 'arena', params: { boxes: 3 } }) });
    expect(created.status).toBe(201);
    const ann = connect(server.wsUrl, { name: 'ann', room: 'arena' });
    const bob = connect(server.wsUrl, { name: 'bob', room: 'arena' });
    clients.push(ann, bob);
    const [wa, wb] = await Promise.all([ann.whenConnected(), bob.whenConnected()]);
    ann.setInput({ ...NEUTRAL_INPUT, moveZ: 127 });

    // The SSE stream delivers samples until one shows both players with a measured RTT, input lead and traffic.
    const abort = new AbortController();
    const events = await fetch(new URL('/monitor/events', url), { headers: auth, signal: abort.signal });
    expect(events.headers.get('content-type')).toMatch(/^text\/event-stream/);
    const reader = events.body!.pipeThrough(new TextDecoderStream()).getReader();
    let buffer = '';
    let live: MonitorState | null = null;
    const deadline = performance.now() + 8000;
    while (performance.now() < deadline) {
      const { value, done } = await reader.read();
      if (done) break;
      buffer += value;
      const blocks = buffer.split('\n\n');
      buffer = blocks.pop()!;
      for (const b of blocks) {
        expect(b.startsWith('event: state\ndata: ')).toBe(true);
        const s = JSON.parse(b.slice('event: state\ndata: '.length)) as MonitorState;
        const room = s.rooms.find((r) => r.id === 'arena');
        if (room && room.players.length === 2 && room.players.every((p) => p.rttMs !== null && p.inputLeadTicks !== null && p.kbpsOut > 0 && p.kbpsIn > 0) && room.ticksPerSecond > 0) live = s;
      }
      if (live) break;
    }
    abort.abort();
    expect(live).not.toBeNull();
    const room = live!.rooms.find((r) => r.id === 'arena')!;
    expect(room).toMatchObject({ scenario: arena.name, params: { boxes: 3 }, netMode: 'snapshot', playerCount: 2, heldCount: 0, closable: true });
    expect(room.players.map((p) => [p.playerId, p.name])).toEqual([
      [wa.playerId, 'ann'],
      [wb.playerId, 'bob'],
    ]);
    expect(room.tickMs!.p99).toBeGreaterThanOrEqual(room.tickMs!.p50);
    expect(room.wasmHeap!.usedBytes).toBeGreaterThan(0);
    expect(room.players.every((p) => Number.isInteger(p.inputLeadTicks) && p.rttMs! >= 0)).toBe(true);
    expect(live!.rooms.find((r) => r.id === 'default')?.closable).toBe(false);

    // The room's player list (open, like the feed that shows the same names) tags characters on the page.
    const players = (await (await fetch(new URL('/api/rooms/arena/players', url))).json()) as { players: unknown[] };
    expect(players.players).toEqual([
      { playerId: wa.playerId, name: 'ann' },
      { playerId: wb.playerId, name: 'bob' },
    ]);
    expect((await fetch(new URL('/api/rooms/nowhere/players', url))).status).toBe(404);

    const metrics = await (await fetch(new URL('/metrics', url), { headers: auth })).text();
    expect(metrics).toMatch(/^taos_room_players\{room="arena",scenario="monitor-arena"\} 2$/m);
    expect(metrics).toMatch(/^taos_room_bodies\{room="arena",scenario="monitor-arena"\} [1-9]/m);

    // Kick: refused without the token, then bob's client ends with "kicked" and the monitor lists ann alone.
    expect((await fetch(new URL(`/monitor/rooms/arena/players/${wb.playerId}/kick`, url), { method: 'POST' })).status).toBe(401);
    const kicked = await fetch(new URL(`/monitor/rooms/arena/players/${wb.playerId}/kick`, url), { method: 'POST', headers: auth });
    expect(kicked.status).toBe(200);
    await waitFor('bob to be closed', () => bob.state === 'closed');
    expect(bob.closed?.reason).toBe('kicked');
    await waitFor('the monitor to list ann alone', async () => (await state(url)).rooms.find((r) => r.id === 'arena')?.players.length === 1);
    const missing = await fetch(new URL('/monitor/rooms/arena/players/99/kick', url), { method: 'POST', headers: auth });
    expect(missing.status).toBe(404);

    // Close: ann's client ends with "room-closed"; the room leaves the monitor and /metrics.
    expect((await fetch(new URL('/monitor/rooms/default/close', url), { method: 'POST', headers: auth })).status).toBe(409);
    const closed = await fetch(new URL('/monitor/rooms/arena/close', url), { method: 'POST', headers: auth });
    expect(closed.status).toBe(200);
    await waitFor('ann to be closed', () => ann.state === 'closed');
    expect(ann.closed?.reason).toBe('room-closed');
    expect((await state(url)).rooms.map((r) => r.id)).toEqual(['default']);
    const after = await (await fetch(new URL('/metrics', url), { headers: auth })).text();
    expect(after).not.toMatch(/room="arena"/);
  });

  it('shows a room that runs in a worker thread, with its players, and closes it', async () => {
    server = await startServer({ port: 0, scenario: 'shape-rain', params: { count: 2 }, roomWorkers: 1, logger: silentLogger(), metrics: createMetrics({ processMetrics: false }), clientDir: '/nonexistent-client-dir' });
    const url = server.url;
    const created = await fetch(new URL('/api/rooms', url), { method: 'POST', headers: { 'content-type': 'application/json' }, body: JSON.stringify({ scenario: 'shape-rain', roomId: 'away', params: { count: 3 } }) });
    expect(created.status).toBe(201);
    const cy = connect(server.wsUrl, { name: 'cy', room: 'away' });
    clients.push(cy);
    await cy.whenConnected();
    const room = async (): Promise<MonitorState['rooms'][number] | undefined> => (await (await fetch(new URL('/monitor/state', url))).json() as MonitorState).rooms.find((r) => r.id === 'away');
    await waitFor('the worker room with its player, ticking', async () => {
      const r = await room();
      return !!r && r.players.length === 1 && r.players[0].rttMs !== null && r.ticksPerSecond > 0;
    });
    const r = (await room())!;
    expect(r).toMatchObject({ worker: 0, scenario: 'shape-rain', params: { count: 3 }, playerCount: 1, tickMs: null });
    expect(r.players[0].name).toBe('cy');
    expect((await fetch(new URL('/monitor/rooms/away/close', url), { method: 'POST' })).status).toBe(200);
    await waitFor('cy to be closed', () => cy.state === 'closed');
    expect(cy.closed?.reason).toBe('room-closed');
  });
});
