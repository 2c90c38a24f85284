// Integration tests for server/start-server.ts on real loopback sockets (port 0): HTTP routes, WebSocket play,
// oversize frames and shutdown byes with rooms on the main thread and in room workers, and a --record session that the
// CLI's replay reproduces hash for hash.
import { mkdtempSync, readdirSync, rmSync } from 'node:fs';
import { tmpdir } from 'node:os';
import { join } from 'node:path';
import { afterAll, afterEach, describe, expect, it } from 'vitest';
import { replayLog } from '../../cli/replay-session.ts';
import { silentLogger } from '../../server/logger.ts';
import { createMetrics } from '../../server/metrics.ts';
import { startServer, type RunningServer } from '../../server/start-server.ts';
import { ByeReason, CharacterQ, ErrorCode } from '../../shared/protocol/index.ts';
import { NEUTRAL_INPUT } from '../../shared/sim/input.ts';
import { scenarioList } from './harness.ts';
import { emptyScenario, stripScenario } from './test-scenarios.ts';
import { WsTestClient } from './ws-client.ts';

const tmp = mkdtempSync(join(tmpdir(), 'taos-srv-'));
afterAll(() => rmSync(tmp, { recursive: true, force: true }));
let server: RunningServer | null = null;
afterEach(async () => {
  await server?.close('test over');
  server = null;
});

/** The test scenes, for room workers (which import their scenarios). */
const TEST_SCENES = new URL('./test-scenarios.ts', import.meta.url).href;

function start(extra: Parameters<typeof startServer>[0] = {}): Promise<RunningServer> {
  return startServer({
    workerScenarioModules: [TEST_SCENES],
    port: 0,
    scenarios: scenarioList([stripScenario, emptyScenario]),
    scenario: 'test-strip',
    logger: silentLogger(),
    metrics: createMetrics({ processMetrics: false }),
    clientDir: join(tmp, 'no-client'),
    ...extra,
  });
}

describe.each([0, 2])('startServer (real sockets, %i room workers)', (roomWorkers) => {
  it('answers /healthz, /api/rooms, /metrics and a not-built page on one port', async () => {
    server = await start({ roomWorkers });
    const health = await fetch(`${server.url}healthz`);
    expect(health.status).toBe(200);
    expect(await health.json()).toMatchObject({ ok: true, rooms: 1, clients: 0 });
    const rooms = (await (await fetch(`${server.url}api/rooms`)).json()) as { rooms: Array<Record<string, unknown>> };
    expect(rooms.rooms).toEqual([expect.objectContaining({ id: 'default', scenario: 'test-strip', clients: 0, tick: 0, bodies: 6 })]);
    const created = await fetch(`${server.url}api/rooms`, { method: 'POST', body: JSON.stringify({ scenario: 'test-empty' }) });
    expect(created.status).toBe(201);
    const { room } = (await created.json()) as { room: { id: string; scenario: string } };
    expect(room.scenario).toBe('test-empty');
    expect((await fetch(`${server.url}api/rooms/${room.id}`)).status).toBe(200);
    const bad = await fetch(`${server.url}api/rooms`, { method: 'POST', body: JSON.stringify({ scenario: 'nope' }) });
    expect(bad.status).toBe(400);
    expect(await bad.json()).toEqual({ error: 'unknown-scenario', message: expect.stringMatching(/^unknown scenario "nope"/) });
    const gone = await fetch(`${server.url}api/rooms/${room.id}`, { method: 'DELETE' });
    expect(gone.status).toBe(200);
    expect((await fetch(`${server.url}api/rooms/${room.id}`)).status).toBe(404);
    const page = await fetch(server.url);
    expect(page.status).toBe(503);
    expect(await page.text()).toMatch(/has not been built/);
    const metrics = await (await fetch(`${server.url}metrics`)).text();
    for (const name of ['taos_tick_duration_seconds_bucket', 'taos_physics_step_seconds', 'taos_rooms 1', 'taos_clients 0', 'taos_inputs_late_total', 'taos_inputs_dropped_total', 'taos_snapshot_bytes', 'taos_bytes_sent_total', 'taos_snapshots_skipped_total', 'taos_tick_overruns_total', 'taos_room_wasm_heap_bytes{room="default",kind="used"}', 'taos_room_slow{room="default"} 0', ...(roomWorkers > 0 ? ['taos_room_worker_rooms{worker="0"}', 'taos_room_worker_cpu_ms_per_tick{worker="1"}'] : [])]) {
      expect(metrics).toContain(name);
    }
  });

  it('plays over WebSocket: two clients see each other move, and shutdown tells both why', async () => {
    server = await start({ snapshotRateHz: 60, roomWorkers });
    const a = await WsTestClient.join(server.wsUrl, 'ann');
    const b = await WsTestClient.join(server.wsUrl, 'bob');
    await b.waitFor(() => b.frames.some((f) => f.playerIds.length === 2), 3000, 'both characters');
    const xOf = (c: WsTestClient, id: number): number => {
      const f = c.frames.at(-1)!;
      const i = Array.from(f.playerIds).indexOf(id);
      return f.characters[i * 11 + CharacterQ.Px];
    };
    const start0 = xOf(b, a.welcome!.playerId);
    const timer = setInterval(() => {
      const tick = (a.frames.at(-1)?.tick ?? 0) + 4;
      a.send({ type: 'input', firstTick: tick, commands: [{ ...NEUTRAL_INPUT, moveX: 127 }, { ...NEUTRAL_INPUT, moveX: 127 }] });
    }, 16);
    try {
      await b.waitFor(() => xOf(b, a.welcome!.playerId) - start0 > 250, 4000, 'ann to move 0.5 m in bob\'s snapshots');
    } finally {
      clearInterval(timer);
    }
    const health = (await (await fetch(`${server.url}healthz`)).json()) as { clients: number };
    expect(health.clients).toBe(2);
    await server.close('maintenance window');
    server = null;
    await a.waitFor(() => a.closed !== null && b.closed !== null, 3000, 'sockets to close');
    for (const c of [a, b]) {
      expect(c.ofType('bye')).toEqual([{ type: 'bye', reason: ByeReason.ServerShutdown, message: 'maintenance window' }]);
      expect(c.closed?.code).toBe(1001);
    }
  });

  it('closes a socket that sends a frame over maxPayload with 1009 and errors on junk', async () => {
    server = await start({ roomWorkers });
    const junk = await WsTestClient.connect(server.wsUrl);
    junk.sendRaw(Uint8Array.of(0xc1, 0xff, 0x00));
    await junk.waitFor(() => junk.messages.length > 0, 3000, 'error message');
    expect(junk.ofType('error')[0]?.code).toBe(ErrorCode.Malformed);
    junk.sendRaw(new Uint8Array(64 * 1024));
    await junk.waitFor(() => junk.closed !== null, 3000, 'close');
    expect(junk.closed?.code).toBe(1009);
    const metrics = await (await fetch(`${server.url}metrics`)).text();
    expect(metrics).toMatch(/taos_disconnects_total\{reason="oversize"\} 1/);
  });
});

describe('startServer recording (real sockets)', () => {
  it('records a served session that replays to identical per-tick hashes', async () => {
    const dir = join(tmp, 'rec');
    server = await startServer({ port: 0, scenario: 'character-course', recordDir: dir, logger: silentLogger(), metrics: createMetrics({ processMetrics: false }), clientDir: join(tmp, 'no-client') });
    const room = server.game.rooms.local('default')!;
    const live = new Map<number, string>();
    room.onTick((record) => live.set(record.tick + 1, room.sim.stateHash()));
    const a = await WsTestClient.join(server.wsUrl, 'ann');
    const b = await WsTestClient.join(server.wsUrl, 'bob');
    let n = 0;
    const timer = setInterval(() => {
      n++;
      const tick = room.sim.tick + 3;
      a.send({ type: 'input', firstTick: tick, commands: [{ ...NEUTRAL_INPUT, moveZ: 127, yaw: (n * 300) & 0xffff, buttons: n % 40 === 0 ? 1 : 0 }] });
      b.send({ type: 'input', firstTick: tick, commands: [{ ...NEUTRAL_INPUT, moveX: n % 60 < 30 ? 127 : -127, buttons: n % 25 === 0 ? 2 : 0 }] });
    }, 16);
    await a.waitFor(() => room.sim.tick > 150, 8000, '150 ticks');
    b.close();
    await a.waitFor(() => room.clientCount === 1, 3000, 'bob to leave');
    await a.waitFor(() => room.sim.tick > 200, 8000, '200 ticks');
    clearInterval(timer);
    await server.close('test over');
    server = null;
    const files = readdirSync(dir).filter((f) => f.endsWith('.taoslog')); // resume keys sit beside each log
    expect(files).toHaveLength(1);
    const report = await replayLog(join(dir, files[0]), { collectHashes: true });
    expect(report.status).toBe('ok');
    expect(report.log).toBe('complete');
    expect(report.ticks).toBe(room.sim.tick);
    expect(report.hashesChecked).toBeGreaterThan(3);
    const hashes = report.hashes!;
    for (const [tick, hash] of live) expect(hashes[tick], `tick ${tick}`).toBe(hash);
    expect(live.size).toBe(report.ticks);
  });

  it('records a session played in a room worker into a log that replays with every recorded hash matching', async () => {
    const dir = join(tmp, 'rec-workers');
    server = await startServer({ port: 0, scenario: 'character-course', recordDir: dir, roomWorkers: 1, logger: silentLogger(), metrics: createMetrics({ processMetrics: false }), clientDir: join(tmp, 'no-client') });
    const a = await WsTestClient.join(server.wsUrl, 'ann');
    const b = await WsTestClient.join(server.wsUrl, 'bob');
    let n = 0;
    const timer = setInterval(() => {
      n++;
      const tick = (a.frames.at(-1)?.tick ?? 0) + 3;
      a.send({ type: 'input', firstTick: tick, commands: [{ ...NEUTRAL_INPUT, moveZ: 127, yaw: (n * 300) & 0xffff, buttons: n % 40 === 0 ? 1 : 0 }] });
      b.send({ type: 'input', firstTick: tick, commands: [{ ...NEUTRAL_INPUT, moveX: n % 60 < 30 ? 127 : -127, buttons: n % 25 === 0 ? 2 : 0 }] });
    }, 16);
    try {
      await a.waitFor(() => (a.frames.at(-1)?.tick ?? 0) > 250, 10_000, '250 ticks');
    } finally {
      clearInterval(timer);
    }
    await server.close('test over');
    server = null;
    const files = readdirSync(dir).filter((f) => f.endsWith('.taoslog')); // resume keys sit beside each log
    expect(files).toHaveLength(1);
    const report = await replayLog(join(dir, files[0]), { collectHashes: true });
    expect(report.status).toBe('ok');
    expect(report.log).toBe('complete');
    expect(report.ticks).toBeGreaterThan(250);
    expect(report.hashesChecked).toBeGreaterThan(3);
  });
});
