// Integration tests for rooms in worker threads (server/workers/): a worker that dies closes only its own rooms with a
// bye that says why while the server keeps serving and replaces it, resume tokens work across the thread boundary,
// and closing rooms gives their WASM memory back.
import { join } from 'node:path';
import { tmpdir } from 'node:os';
import { afterEach, describe, expect, it } from 'vitest';
import { silentLogger } from '../../../server/logger.ts';
import { createMetrics } from '../../../server/metrics.ts';
import { startServer, type RunningServer } from '../../../server/start-server.ts';
import { ByeReason, PROTOCOL_VERSION } from '../../../shared/protocol/index.ts';
import { scenarioList } from '../harness.ts';
import { emptyScenario, stripScenario } from '../test-scenarios.ts';
import { WsTestClient } from '../ws-client.ts';

const TEST_SCENES = new URL('../test-scenarios.ts', import.meta.url).href;
const MODULE_BYTES = 128 * 1024 * 1024;

let server: RunningServer | null = null;
const clients: WsTestClient[] = [];
afterEach(async () => {
  for (const c of clients.splice(0)) c.close();
  await server?.close('test over');
  server = null;
});

function start(roomWorkers: number): Promise<RunningServer> {
  return startServer({
    port: 0,
    roomWorkers,
    workerScenarioModules: [TEST_SCENES],
    scenarios: scenarioList([stripScenario, emptyScenario]),
    scenario: 'test-strip',
    logger: silentLogger(),
    metrics: createMetrics({ processMetrics: false }),
    clientDir: join(tmpdir(), 'taos-no-client'),
  });
}

async function waitUntil(what: string, timeoutMs: number, done: () => boolean | Promise<boolean>): Promise<void> {
  const deadline = performance.now() + timeoutMs;
  while (!(await done())) {
    if (performance.now() > deadline) throw new Error(`timed out waiting for ${what}`);
    await new Promise((r) => setTimeout(r, 25));
  }
}

describe('room workers', () => {
  it('closes only the rooms of a worker that dies, tells their players why, and keeps serving with a replacement worker', async () => {
    server = await start(2);
    const workers = server.game.workers!;
    const arena = await fetch(`${server.url}api/rooms`, { method: 'POST', body: JSON.stringify({ roomId: 'arena', scenario: 'test-strip' }) });
    expect(arena.status).toBe(201);
    const home = workers.workers().find((t) => t.rooms.has('default'))!;
    const doomed = workers.workers().find((t) => t.rooms.has('arena'))!;
    expect(doomed.index).not.toBe(home.index);
    const calm = await WsTestClient.join(server.wsUrl, 'calm');
    const victim = await WsTestClient.join(server.wsUrl, 'victim', 'arena');
    clients.push(calm, victim);
    await victim.waitFor(() => victim.frames.length > 2, 5000, 'arena snapshots');

    await doomed.worker.terminate();
    await victim.waitFor(() => victim.closed !== null, 5000, 'the arena player to be disconnected');
    const bye = victim.ofType('bye')[0];
    expect(bye?.reason).toBe(ByeReason.RoomClosed);
    expect(bye?.message).toMatch(/worker thread stopped/);
    const framesBefore = calm.frames.length;
    await calm.waitFor(() => calm.frames.length > framesBefore + 10, 5000, 'the default room to go on');
    expect(calm.closed).toBeNull();
    const rooms = (await (await fetch(`${server.url}api/rooms`)).json()) as { rooms: Array<{ id: string }> };
    expect(rooms.rooms.map((r) => r.id)).toEqual(['default']);

    await waitUntil('a replacement worker', 10_000, () => workers.workers().length === 2);
    const again = await fetch(`${server.url}api/rooms`, { method: 'POST', body: JSON.stringify({ roomId: 'arena', scenario: 'test-strip' }) });
    expect(again.status).toBe(201);
    const back = await WsTestClient.join(server.wsUrl, 'back', 'arena');
    clients.push(back);
    await back.waitFor(() => back.frames.length > 2, 5000, 'snapshots from the reopened arena');
  });

  it('opens the default room again when its worker dies', async () => {
    server = await start(2);
    const workers = server.game.workers!;
    const calm = await WsTestClient.join(server.wsUrl, 'calm');
    clients.push(calm);
    await workers.workers().find((t) => t.rooms.has('default'))!.worker.terminate();
    await calm.waitFor(() => calm.closed !== null, 5000, 'the default room player to be disconnected');
    expect(calm.ofType('bye')[0]?.message).toMatch(/worker thread stopped/);
    await waitUntil('the default room to reopen', 10_000, () => server!.game.rooms.get('default') !== undefined);
    const again = await WsTestClient.join(server.wsUrl, 'again');
    clients.push(again);
    expect(again.welcome?.roomId).toBe('default');
    await again.waitFor(() => again.frames.length > 2, 5000, 'snapshots from the reopened default room');
  });

  it('holds a player whose link was cut and gives it back to a connection with its resume token', async () => {
    server = await start(2);
    const first = await WsTestClient.join(server.wsUrl, 'ann');
    clients.push(first);
    await first.waitFor(() => first.frames.length > 2, 5000, 'snapshots');
    const { playerId, resumeToken } = first.welcome!;
    expect(resumeToken).toEqual(expect.any(String));
    first.ws.terminate(); // no close frame: the server holds the player
    await waitUntil('the server to hold the player', 5000, async () => {
      const list = (await (await fetch(`${server!.url}api/rooms`)).json()) as { rooms: Array<{ id: string; clients: number }> };
      return list.rooms[0].clients === 1 && server!.game.sessionCount() === 0;
    });
    const back = await WsTestClient.connect(server.wsUrl);
    clients.push(back);
    back.send({ type: 'hello', version: PROTOCOL_VERSION, name: 'ann', room: null, resumeToken: resumeToken! });
    await back.waitFor(() => back.welcome !== null || back.closed !== null, 5000, 'the welcome');
    expect(back.welcome).toMatchObject({ playerId, resumed: true, roomId: 'default' });
    await back.waitFor(() => back.frames.some((f) => Array.from(f.playerIds).includes(playerId)), 5000, 'the same character in snapshots');
    expect(back.ofType('error')).toEqual([]);
  });

  it('gives back the WASM memory of rooms closed in a worker', async () => {
    server = await start(1);
    const worker = server.game.workers!.workers()[0];
    await waitUntil('a first memory report', 5000, () => worker.externalBytes > 0);
    const baseline = worker.externalBytes;
    const ROOMS = 6;
    for (let i = 0; i < ROOMS; i++) {
      const opened = await fetch(`${server.url}api/rooms`, { method: 'POST', body: JSON.stringify({ roomId: `churn-${i}`, scenario: 'test-empty' }) });
      expect(opened.status).toBe(201);
      await waitUntil(`room churn-${i}'s module in the worker's memory`, 5000, () => worker.externalBytes >= baseline + 0.9 * MODULE_BYTES);
      if (i % 2 === 0) {
        const c = await WsTestClient.join(server.wsUrl, `p${i}`, `churn-${i}`);
        clients.push(c);
        await c.waitFor(() => c.frames.length >= 2, 5000, 'snapshots');
      }
      expect((await fetch(`${server.url}api/rooms/churn-${i}`, { method: 'DELETE' })).status).toBe(200);
    }
    // Six 128 MiB modules were made and dropped; held, they would keep the worker's external memory ≥ 6 × 128 MiB.
    await waitUntil('the closed rooms\u2019 modules to be freed', 20_000, () => worker.externalBytes < baseline + 2 * MODULE_BYTES);
    expect(worker.externalBytes).toBeLessThan(baseline + 2 * MODULE_BYTES);
  });
});
