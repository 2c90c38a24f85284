// The isolation test of rooms in worker threads: three heavy rooms at their maximum parameters (shape-rain,
// height-field, convex-hulls), one member each, beside the light default room with one player. The light room must
// hold ≥ 58 ticks/s with its tick p99 < 16.7 ms and /api/rooms must answer within 200 ms, whether the heavy rooms run
// (slowed, and saying so) or are refused for capacity. Figures come from the server's own room list.
// The machine this runs on may be loaded by others, and its load drifts: the light room is measured in alternating
// windows, heavy rooms running (their members in) and paused (their members out), and the running windows are judged
// against the paused ones: at most 2 ticks/s lost where the light room alone keeps 60, a tick's CPU time < 16.7 ms
// absolutely, wall-time p99 and the API's answer time against 4× the paused windows' (the storm test's rule).
import { join } from 'node:path';
import { tmpdir } from 'node:os';
import { afterEach, describe, expect, it } from 'vitest';
import WebSocket from 'ws';
import { listScenarios } from '../../../scenarios/index.ts';
import { silentLogger } from '../../../server/logger.ts';
import { createMetrics } from '../../../server/metrics.ts';
import type { RoomInfo } from '../../../server/room.ts';
import { startServer, type RunningServer } from '../../../server/start-server.ts';
import { encodeClientMessage, PROTOCOL_VERSION } from '../../../shared/protocol/index.ts';
import { NEUTRAL_INPUT } from '../../../shared/sim/input.ts';
import { TICK_MS } from '../../../shared/tick-rate.ts';
import { WsTestClient } from '../ws-client.ts';

const HEAVY = ['shape-rain', 'height-field', 'convex-hulls'] as const;
const ROUNDS = 3;
const WINDOW_MS = 2500;

let server: RunningServer | null = null;
const sockets: WebSocket[] = [];
afterEach(async () => {
  for (const s of sockets.splice(0)) s.terminate();
  await server?.close('test over');
  server = null;
});

/** Every parameter of a scenario at its maximum. */
function maxParams(name: string): Record<string, number> {
  const def = listScenarios().find((s) => s.name === name)!;
  return Object.fromEntries(Object.entries(def.params).map(([k, p]) => [k, p.max]));
}

/** A member that joins a room and reads its bytes without decoding them (the heavy rooms' one player each). */
function member(url: string, room: string): Promise<WebSocket> {
  return new Promise((resolve, reject) => {
    const ws = new WebSocket(url, { perMessageDeflate: false });
    sockets.push(ws);
    ws.on('open', () => ws.send(encodeClientMessage({ type: 'hello', version: PROTOCOL_VERSION, name: `in-${room}`, room })));
    ws.once('message', () => resolve(ws));
    ws.on('error', reject);
  });
}

async function rooms(url: string): Promise<{ list: RoomInfo[]; ms: number }> {
  const t0 = performance.now();
  const res = await fetch(`${url}api/rooms`);
  const body = (await res.json()) as { rooms: RoomInfo[] };
  return { list: body.rooms, ms: performance.now() - t0 };
}

/** Totals of the light room over some windows: ticks, seconds, answer times of /api/rooms, and its last report. */
interface Phase {
  ticks: number;
  seconds: number;
  apiMs: number[];
  light: RoomInfo | null;
}

/** One window: the light room's ticks from its tick counter while /api/rooms is polled every 200 ms. */
async function window(url: string, into: Phase): Promise<void> {
  const first = await rooms(url);
  const startTick = first.list.find((r) => r.id === 'default')!.tick;
  const startMs = performance.now();
  into.apiMs.push(first.ms);
  while (performance.now() - startMs < WINDOW_MS) {
    await new Promise((r) => setTimeout(r, 200));
    into.apiMs.push((await rooms(url)).ms);
  }
  const last = await rooms(url);
  into.apiMs.push(last.ms);
  into.light = last.list.find((r) => r.id === 'default')!;
  into.ticks += into.light.tick - startTick;
  into.seconds += (performance.now() - startMs) / 1000;
}

const p99 = (xs: number[]): number => [...xs].sort((a, b) => a - b)[Math.min(xs.length - 1, Math.floor(xs.length * 0.99))];

describe('room isolation with room workers', () => {
  it('keeps the light room at 60 Hz and the room list quick beside three heavy rooms at maximum parameters', async () => {
    server = await startServer({ port: 0, roomWorkers: 2, logger: silentLogger(), metrics: createMetrics({ processMetrics: false }), clientDir: join(tmpdir(), 'taos-no-client') });
    const url = server.url;
    const player = await WsTestClient.join(server.wsUrl, 'light');
    const inputs = setInterval(() => {
      const tick = (player.frames.at(-1)?.tick ?? 0) + 3;
      player.send({ type: 'input', firstTick: tick, commands: [{ ...NEUTRAL_INPUT, moveZ: 127 }] });
    }, TICK_MS);
    try {
      const outcome = new Map<string, { status: number; id?: string; message?: string }>();
      for (const scenario of HEAVY) {
        const res = await fetch(`${url}api/rooms`, { method: 'POST', body: JSON.stringify({ scenario, params: maxParams(scenario) }) });
        const body = (await res.json()) as { room?: RoomInfo; message?: string };
        outcome.set(scenario, { status: res.status, id: body.room?.id, message: body.message });
      }
      for (const [scenario, o] of outcome) {
        expect([201, 503], `${scenario}: ${o.message ?? ''}`).toContain(o.status);
        if (o.status === 503) expect(o.message).toMatch(new RegExp(`no capacity for another ${scenario} room`));
      }
      const running = [...outcome.values()].filter((o) => o.status === 201).map((o) => o.id!);

      const paused: Phase = { ticks: 0, seconds: 0, apiMs: [], light: null };
      const loaded: Phase = { ticks: 0, seconds: 0, apiMs: [], light: null };
      let heavyInfo: RoomInfo[] = [];
      const perRound: string[] = [];
      for (let round = 0; round < ROUNDS; round++) {
        const p0 = { t: paused.ticks, s: paused.seconds };
        const l0 = { t: loaded.ticks, s: loaded.seconds };
        await window(url, paused);
        const members = await Promise.all(running.map((id) => member(server!.wsUrl, id)));
        await new Promise((r) => setTimeout(r, 1000)); // the heavy rooms get going
        await window(url, loaded);
        heavyInfo = (await rooms(url)).list.filter((r) => r.id !== 'default');
        perRound.push(`${((paused.ticks - p0.t) / (paused.seconds - p0.s)).toFixed(1)}/${((loaded.ticks - l0.t) / (loaded.seconds - l0.s)).toFixed(1)}`);
        for (const m of members) m.close(1000); // a clean leave: the heavy rooms empty and pause
        await new Promise((r) => setTimeout(r, 500));
      }
      const quietRate = paused.ticks / paused.seconds;
      const loadedRate = loaded.ticks / loaded.seconds;
      const light = loaded.light!;
      const quietWallP99 = paused.light!.tickMsP99!;
      const summary = `rounds (paused/running ticks/s) ${perRound.join(' ')}; paused: ${quietRate.toFixed(1)} ticks/s, API p99 ${p99(paused.apiMs).toFixed(0)} ms; running: ${loadedRate.toFixed(1)} ticks/s, tick p99 ${light.tickMsP99} ms wall (paused ${quietWallP99}), ${light.tickCpuMsP99} ms CPU, API max ${Math.max(...loaded.apiMs).toFixed(0)} ms; heavy ${JSON.stringify(heavyInfo.map((r) => [r.id, r.ticksPerSecond, r.slow]))}; ${JSON.stringify([...outcome])}`;
      console.info(`isolation: ${summary}`);

      // ≥ 58 ticks/s where the room alone keeps 60 (at most 2 ticks/s lost to the heavy rooms), tick p99 < 16.7 ms.
      expect(loadedRate, summary).toBeGreaterThanOrEqual(Math.min(quietRate, 60) - 2);
      expect(light.tickCpuMsP99!, summary).toBeLessThan(16.7);
      expect(light.tickMsP99!, summary).toBeLessThan(Math.max(16.7, 4 * quietWallP99));
      expect(Math.max(...loaded.apiMs), summary).toBeLessThan(Math.max(200, 4 * p99(paused.apiMs)));
      // A heavy room that runs below the tick rate says so.
      for (const r of heavyInfo) if (r.ticksPerSecond < 55) expect(r.slow, `${r.id} at ${r.ticksPerSecond} ticks/s`).toBe(true);
      expect(player.closed).toBeNull();
    } finally {
      clearInterval(inputs);
    }
  });
});
