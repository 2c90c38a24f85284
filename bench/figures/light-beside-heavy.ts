// The light room beside heavy rooms: the default room (character-course, one member) while N = 0…3 heavy rooms at
// every parameter's maximum (shape-rain, height-field, convex-hulls; one member each) open beside it, with every room
// on the main thread's one event loop and with 2 room workers. Per N: the light room's ticks per second (its tick
// counter over the window), its tick p99s (wall and CPU, from the room list), and how long GET /api/rooms takes.
// A ladder stops early once the API takes over STARVED_API_MS or fails: the loop is starved, heavier steps only starve
// it more (and take minutes).
import WebSocket from 'ws';
import { listScenarios } from '../../scenarios/index.ts';
import { silentLogger } from '../../server/logger.ts';
import { createMetrics } from '../../server/metrics.ts';
import type { RoomInfo } from '../../server/room.ts';
import { startServer, type RunningServer } from '../../server/start-server.ts';
import { encodeClientMessage, PROTOCOL_VERSION } from '../../shared/protocol/index.ts';
import type { FigureImpl, FigureOutput, ReportRow } from '../lib/figure.ts';
import { quantile, round } from '../lib/stats.ts';

const HEAVY = ['shape-rain', 'height-field', 'convex-hulls'] as const;
const ROOM_WORKERS = 2;
const STARVED_API_MS = 2000;

interface Step {
  roomWorkers: number;
  heavyRooms: number;
  /** Heavy rooms refused for capacity (503). */
  refused: number;
  lightTicksPerSecond: number;
  lightTickMsP99: number | null;
  lightTickCpuMsP99: number | null;
  apiMsP99: number;
  apiMsMax: number;
}

function maxParams(name: string): Record<string, number> {
  const def = listScenarios().find((s) => s.name === name)!;
  return Object.fromEntries(Object.entries(def.params).map(([k, p]) => [k, p.max]));
}

/** A member that joins a room and reads its bytes without decoding them. */
function member(url: string, room: string | null, sockets: WebSocket[]): Promise<void> {
  return new Promise((resolve, reject) => {
    const ws = new WebSocket(url, { perMessageDeflate: false });
    sockets.push(ws);
    ws.on('open', () => ws.send(encodeClientMessage({ type: 'hello', version: PROTOCOL_VERSION, name: 'member', room })));
    ws.once('message', () => resolve());
    ws.on('error', reject);
  });
}

async function rooms(url: string): Promise<{ list: RoomInfo[]; ms: number }> {
  const t0 = performance.now();
  const body = (await (await fetch(`${url}api/rooms`)).json()) as { rooms: RoomInfo[] };
  return { list: body.rooms, ms: performance.now() - t0 };
}

async function ladder(roomWorkers: number, settleMs: number, windowMs: number, log: (m: string) => void): Promise<Step[]> {
  const sockets: WebSocket[] = [];
  let server: RunningServer | null = null;
  const steps: Step[] = [];
  try {
    server = await startServer({ port: 0, roomWorkers, maxRooms: 8, logger: silentLogger(), metrics: createMetrics({ processMetrics: false }), clientDir: '/nonexistent' });
    await member(server.wsUrl, null, sockets);
    let refused = 0;
    for (let n = 0; n <= HEAVY.length; n++) {
      if (steps.length > 0 && steps.at(-1)!.apiMsMax > STARVED_API_MS) {
        log(`stopping: /api/rooms took ${steps.at(-1)!.apiMsMax} ms (the loop is starved)`);
        break;
      }
      if (n > 0) {
        const scenario = HEAVY[n - 1];
        const res = await fetch(`${server.url}api/rooms`, { method: 'POST', body: JSON.stringify({ scenario, params: maxParams(scenario) }) });
        const body = (await res.json()) as { room?: RoomInfo };
        if (res.status === 201) await member(server.wsUrl, body.room!.id, sockets);
        else refused++;
      }
      await new Promise((r) => setTimeout(r, settleMs));
      const first = await rooms(server.url);
      const startTick = first.list.find((r) => r.id === 'default')!.tick;
      const startMs = performance.now();
      const apiMs = [first.ms];
      while (performance.now() - startMs < windowMs) {
        await new Promise((r) => setTimeout(r, 100));
        apiMs.push((await rooms(server.url)).ms);
      }
      const last = await rooms(server.url);
      apiMs.push(last.ms);
      const light = last.list.find((r) => r.id === 'default')!;
      const step: Step = {
        roomWorkers,
        heavyRooms: n,
        refused,
        lightTicksPerSecond: round((light.tick - startTick) / ((performance.now() - startMs) / 1000), 1),
        lightTickMsP99: light.tickMsP99,
        lightTickCpuMsP99: light.tickCpuMsP99,
        apiMsP99: round(quantile(apiMs, 0.99), 1),
        apiMsMax: round(Math.max(...apiMs), 1),
      };
      steps.push(step);
      log(`${roomWorkers === 0 ? 'one thread' : `${roomWorkers} workers`}, ${n} heavy (${refused} refused): light ${step.lightTicksPerSecond} ticks/s, tick p99 ${step.lightTickMsP99} ms (CPU ${step.lightTickCpuMsP99} ms), API p99 ${step.apiMsP99} ms`);
    }
  } catch (error) {
    log(`stopping: ${error instanceof Error ? error.message : String(error)} (the server is starved)`);
  } finally {
    for (const s of sockets) s.terminate();
    await server?.close('bench done');
  }
  return steps;
}

async function run(opts: { quick: boolean; log(m: string): void }): Promise<FigureOutput> {
  const settleMs = opts.quick ? 1500 : 3000;
  const windowMs = opts.quick ? 3000 : 6000;
  const oneThread = await ladder(0, settleMs, windowMs, opts.log);
  const workers = await ladder(ROOM_WORKERS, settleMs, windowMs, opts.log);
  const at3 = (steps: Step[]): Step | undefined => steps.find((s) => s.heavyRooms === HEAVY.length);
  const rows: ReportRow[] = [];
  for (const s of [...oneThread, ...workers]) {
    const where = s.roomWorkers === 0 ? 'one thread' : `${s.roomWorkers} workers`;
    const refused = s.refused > 0 ? `, ${s.refused} refused` : '';
    rows.push({ figure: 'light room beside heavy', measure: `${where}, ${s.heavyRooms} heavy rooms${refused}: light room ticks/s`, value: s.lightTicksPerSecond, unit: '/s', digits: 1, goal: { op: '>=', value: 58 } });
    rows.push({ figure: 'light room beside heavy', measure: `${where}, ${s.heavyRooms} heavy rooms${refused}: light tick p99 (wall)`, value: s.lightTickMsP99, unit: 'ms', digits: 2, goal: { op: '<=', value: 16.7 } });
    rows.push({ figure: 'light room beside heavy', measure: `${where}, ${s.heavyRooms} heavy rooms${refused}: GET /api/rooms max`, value: s.apiMsMax, unit: 'ms', digits: 0, goal: { op: '<=', value: 200 } });
  }
  return {
    headline: {
      lightTicksPerSecondBesideHeavy: at3(workers)?.lightTicksPerSecond ?? null,
      lightTickP99MsBesideHeavy: at3(workers)?.lightTickMsP99 ?? null,
      lightTicksPerSecondBesideHeavyOneThread: at3(oneThread)?.lightTicksPerSecond ?? null,
    },
    detail: { heavy: HEAVY, roomWorkers: ROOM_WORKERS, settleMs, windowMs, steps: [...oneThread, ...workers] },
    rows,
    charts: [
      {
        title: 'Light room ticks per second beside N heavy rooms at maximum parameters (one thread vs room workers)',
        unit: '/s',
        goal: 58,
        bars: [...oneThread, ...workers].map((s) => ({ label: `${s.roomWorkers === 0 ? 'one thread' : 'workers'}, ${s.heavyRooms} heavy`, value: s.lightTicksPerSecond, series: s.roomWorkers === 0 ? ('baseline' as const) : ('ours' as const) })),
      },
    ],
    notes: [
      `In-process servers (port 0): the default room (character-course) with one member; heavy rooms ${HEAVY.join(', ')} at every parameter's maximum open one per step, each with one member, first all on the main thread, then in ${ROOM_WORKERS} room workers (placement by CPU per tick: a heavy room gets an idle worker or is refused with 503). Each step settles ${settleMs} ms, then measures ${windowMs} ms: the light room's ticks from its tick counter, its tick p99s from the room list (last 600 ticks), /api/rooms polled every 100 ms. Not pinned: the machine's load shows in every figure.`,
    ],
  };
}

/** The light-beside-heavy figure. */
export const figure: FigureImpl = { run };
