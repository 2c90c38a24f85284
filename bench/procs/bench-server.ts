// The server process of the clients-per-core and rooms-per-core figures: startServer (HTTP + ws on loopback, the
// scene's default room) with the connection caps (total and per address), room caps and, on the main thread, the scene's player
// cap (players.maxPlayers: the figure measures what the server can serve, beside what the scene declares) lifted, every room's ticks timed (wall and this thread's
// CPU), GC pauses observed, the process's own CPU time counted. Prints {"wsUrl"} when listening. Stdin commands:
// "rooms N" opens rooms r1…rN of the same scene (prints {"rooms"}); "mark" starts a measurement window; "report"
// prints the window as one JSON line. With ROOM_WORKERS > 0 the rooms run in worker threads and their figures come
// from the server's own room list (pace: ticks, tick p99s, longest gap between tick starts) and their GC pauses from
// the workers' status reports.
// Investigation aids (bench/rooms-probe.ts): BENCH_DUMP=FILE writes every main-thread room tick of a window (start,
// lateness, wall, CPU) and each GC pause with its kind; BENCH_HEAP_PROF=FILE samples the window's allocations (with
// BENCH_HEAP_PROF_LIVE=1 only those still alive at its end).
// Run: node bench/procs/bench-server.ts SCENARIO PARAMS_JSON SNAPSHOT_HZ MAX_CLIENTS [ROOM_WORKERS]
import { constants, PerformanceObserver } from 'node:perf_hooks';
import { createInterface } from 'node:readline';
import type { Room } from '../../server/room.ts';
import { scenarioSource } from '../../server/create-server.ts';
import { silentLogger } from '../../server/logger.ts';
import { listScenarios } from '../../scenarios/index.ts';
import { createMetrics } from '../../server/metrics.ts';
import { GC_PAUSE_FIELDS, STATUS_INTERVAL_MS } from '../../server/workers/worker-protocol.ts';
import { startServer } from '../../server/start-server.ts';
import { gcPausePerTick, maxGap, type GcPause } from '../lib/rules.ts';
import { quantile, round } from '../lib/stats.ts';

const [scenario, paramsJson, rateArg, maxArg, workersArg] = process.argv.slice(2);
const roomWorkers = Number(workersArg ?? 0);
const snapshotRateHz = Number(rateArg);
const maxClients = Number(maxArg);
if (!scenario || !paramsJson || !Number.isInteger(snapshotRateHz) || !Number.isInteger(maxClients) || !Number.isInteger(roomWorkers)) {
  process.stderr.write('usage: node bench/procs/bench-server.ts SCENARIO PARAMS_JSON SNAPSHOT_HZ MAX_CLIENTS [ROOM_WORKERS]\n');
  process.exit(2);
}
const params = JSON.parse(paramsJson) as Record<string, number>;
const MAX_ROOMS = 64;

const metrics = createMetrics({ processMetrics: false });
const server = await startServer({
  port: 0,
  host: '127.0.0.1',
  scenario,
  params,
  snapshotRateHz,
  maxClients,
  maxConnections: maxClients + 16,
  maxRooms: MAX_ROOMS + 1,
  emptyRoomGraceMs: 3_600_000, // rooms of the ladder stay open between steps
  // Every bot comes from 127.0.0.1: lift the per-address connection caps.
  connectionPolicy: { maxSocketsPerAddress: Infinity, maxPendingPerAddress: Infinity },
  logger: silentLogger(),
  metrics,
  roomWorkers,
  // Room workers build their scenarios from the registry by name, so only main-thread rooms get the lifted cap.
  ...(roomWorkers === 0 ? { scenarios: scenarioSource(listScenarios().map((def) => (def.name === scenario ? { ...def, players: { ...def.players, maxPlayers: maxClients } } : def))) } : {}),
  // A/B lever for the rooms' GC: BENCH_WORKER_YOUNG_MB sets the room workers' young generation (default V8's).
  roomWorkerYoungGenerationMb: process.env.BENCH_WORKER_YOUNG_MB ? Number(process.env.BENCH_WORKER_YOUNG_MB) : undefined,
});

/**
 * A growing column of numbers outside the JS heap. Plain arrays of doubles, regrown as they filled, were survivors of
 * every scavenge of the server they measure (each regrowth a fresh young copy of the whole column, one per field per room).
 */
class Column {
  private data = new Float64Array(4096);
  private n = 0;

  push(value: number): void {
    if (this.n === this.data.length) {
      const grown = new Float64Array(this.data.length * 2);
      grown.set(this.data);
      this.data = grown;
    }
    this.data[this.n++] = value;
  }

  get length(): number {
    return this.n;
  }

  clear(): void {
    this.n = 0;
  }

  values(): number[] {
    return Array.from(this.data.subarray(0, this.n));
  }
}

interface TickLog {
  room: Room;
  startsMs: Column;
  /** How late each tick started after it was due (ms), and this thread's CPU time (ms) when it started. */
  lateMs: Column;
  cpuAtStartMs: Column;
  wallMs: Column;
  cpuMs: Column;
}
const logs: TickLog[] = [];

/** Times every tick of a room: its start, its wall time and this thread's CPU time inside it. */
function instrument(room: Room): void {
  const log: TickLog = { room, startsMs: new Column(), lateMs: new Column(), cpuAtStartMs: new Column(), wallMs: new Column(), cpuMs: new Column() };
  logs.push(log);
  const tickOnce = room.tickOnce.bind(room);
  room.tickOnce = () => {
    const c0 = process.threadCpuUsage();
    const t0 = performance.now();
    tickOnce();
    const wall = performance.now() - t0;
    const cpu = process.threadCpuUsage(c0);
    log.startsMs.push(t0);
    log.lateMs.push(t0 - (room.tickClock.nextDueMs() - room.tickClock.dtMs));
    log.cpuAtStartMs.push((c0.user + c0.system) / 1000);
    log.wallMs.push(wall);
    log.cpuMs.push((cpu.user + cpu.system) / 1000);
  };
}
const defaultRoom = server.game.rooms.local('default');
if (defaultRoom) instrument(defaultRoom);
else if (roomWorkers === 0) throw new Error('bench-server: no default room');
/** Rooms in workers: their tick counters at the window's mark. */
let ticksAtMark = new Map<string, number>();

const pauses: GcPause[] = [];
/** Investigation aid: with BENCH_DUMP=FILE, report() also writes every room tick and GC pause (with its kind) of the window there. */
const kinds: number[] = [];
const gcObserver = new PerformanceObserver((list) => {
  for (const e of list.getEntries()) {
    const kind = (e as PerformanceEntry & { detail?: { kind?: number } }).detail?.kind;
    pauses.push({ startTime: e.startTime, duration: e.duration, major: kind === constants.NODE_PERFORMANCE_GC_MAJOR });
    kinds.push(kind ?? -1);
  }
});
gcObserver.observe({ entryTypes: ['gc'] });

/** Counters summed over this thread's registry and every room worker's (snapshots and ticks are counted where rooms run). */
async function counters(): Promise<Record<'sent' | 'skipped' | 'ticksSkipped' | 'messagesIn' | 'bytesIn' | 'bytesOut', number>> {
  const registries = [await metrics.registry.getMetricsAsJSON(), ...(server.game.workers ? await server.game.workers.metricsJson() : [])] as Array<Array<{ name: string; values: Array<{ value: number }> }>>;
  const sum = (name: string): number => registries.flat().filter((m) => m.name === name).reduce((s, m) => s + m.values.reduce((a, v) => a + v.value, 0), 0);
  return {
    sent: sum('taos_snapshots_sent_total'),
    skipped: sum('taos_snapshots_skipped_total'),
    ticksSkipped: sum('taos_ticks_skipped_total'),
    messagesIn: sum('taos_messages_received_total'),
    bytesIn: sum('taos_bytes_received_total'),
    bytesOut: sum('taos_bytes_sent_total'),
  };
}

const summary = (xs: number[]): { p50: number; p99: number; max: number } | null =>
  xs.length === 0 ? null : { p50: round(quantile(xs, 0.5), 3), p99: round(quantile(xs, 0.99), 3), max: round(Math.max(...xs), 3) };

const inspector = process.env.BENCH_HEAP_PROF ? new (await import('node:inspector')).Session() : null;
inspector?.connect();
/** Investigation aid: with BENCH_HEAP_PROF=FILE, the window's allocations (collected ones too) are sampled into FILE. */
function heapSampling(method: string, params: object): Promise<unknown> {
  return new Promise((resolve, reject) => inspector!.post(method, params, (err, res) => (err ? reject(err) : resolve(res))));
}

let mark = { atMs: performance.now(), cpu: process.cpuUsage(), mainCpu: process.threadCpuUsage(), ...(await counters()) };

async function openRooms(n: number): Promise<string[]> {
  if (!Number.isInteger(n) || n < 0 || n > MAX_ROOMS) throw new Error(`bench-server: rooms must be in [0, ${MAX_ROOMS}], got ${n}`);
  const ids: string[] = [];
  for (let i = 1; i <= n; i++) {
    const id = `r${i}`;
    ids.push(id);
    if (server.game.rooms.get(id)) continue;
    await server.game.rooms.create(id, scenario, params);
    const room = server.game.rooms.local(id);
    if (room) instrument(room);
  }
  return ids;
}

/** Rooms in workers as the server's room list tells them (tick p99s and the longest gap cover their last 600 ticks). */
function workerRooms(): unknown[] {
  return server.game.rooms
    .list()
    .filter((r) => ticksAtMark.has(r.id) && (r.clients > 0 || r.tick > ticksAtMark.get(r.id)!))
    .map((r) => ({
      id: r.id,
      clients: r.clients,
      bodies: r.bodies,
      ticks: r.tick - ticksAtMark.get(r.id)!,
      cpuMsTotal: null,
      tickWallMs: r.tickMsP99 === null ? null : { p50: null, p99: r.tickMsP99, max: null },
      tickCpuMs: r.tickCpuMsP99 === null ? null : { p50: null, p99: r.tickCpuMsP99, max: null },
      maxGapMs: r.tickGapMsMax,
    }));
}

/** The room workers' GC pauses that started in [fromMs, toMs) of this thread's performance clock, all workers merged. */
function workerGcPauses(fromMs: number, toMs: number): GcPause[] {
  const out: GcPause[] = [];
  for (const t of server.game.workers?.workers() ?? []) {
    for (let i = 0; i < t.gcPauses.length; i += GC_PAUSE_FIELDS) {
      const startTime = t.gcPauses[i] - performance.timeOrigin;
      if (startTime >= fromMs && startTime < toMs) out.push({ startTime, duration: t.gcPauses[i + 1], major: t.gcPauses[i + 2] === constants.NODE_PERFORMANCE_GC_MAJOR });
    }
  }
  return out.sort((a, b) => a.startTime - b.startTime);
}

/** GC pauses of one window: count, total, longest, and the p99 of the pause time per tick-length interval. */
function gcSummary(fromMs: number, toMs: number, windowPauses: readonly GcPause[]): { pauses: number; totalMs: number; maxMs: number; perTickP99Ms: number; majorPauses: number | null; majorMaxMs: number | null } {
  const kinds = windowPauses.filter((p) => p.major !== undefined);
  const majors = kinds.filter((p) => p.major);
  return {
    majorPauses: kinds.length > 0 ? majors.length : null,
    majorMaxMs: kinds.length > 0 ? round(majors.reduce((m, p) => Math.max(m, p.duration), 0), 3) : null,
    pauses: windowPauses.length,
    totalMs: round(windowPauses.reduce((s, p) => s + p.duration, 0), 3),
    maxMs: round(windowPauses.reduce((m, p) => Math.max(m, p.duration), 0), 3),
    perTickP99Ms: round(quantile(gcPausePerTick(fromMs, toMs, windowPauses), 0.99), 3),
  };
}

async function report(): Promise<unknown> {
  const endMs = performance.now();
  const cpu = process.cpuUsage(mark.cpu);
  const mainCpu = process.threadCpuUsage(mark.mainCpu);
  const inWorkers = roomWorkers > 0 ? workerRooms() : [];
  const now = await counters();
  // Workers push their GC pauses with their status: wait two status intervals so the window's last ones are in.
  if (roomWorkers > 0) await new Promise((r) => setTimeout(r, 2 * STATUS_INTERVAL_MS));
  const seconds = (endMs - mark.atMs) / 1000;
  const windowPauses = pauses.filter((p) => p.startTime >= mark.atMs && p.startTime < endMs);
  const mainGc = gcSummary(mark.atMs, endMs, windowPauses);
  if (process.env.BENCH_HEAP_PROF) {
    const { profile } = (await heapSampling('HeapProfiler.stopSampling', {})) as { profile: unknown };
    (await import('node:fs')).writeFileSync(process.env.BENCH_HEAP_PROF, JSON.stringify(profile));
  }
  if (process.env.BENCH_DUMP) {
    const { writeFileSync } = await import('node:fs');
    writeFileSync(process.env.BENCH_DUMP, JSON.stringify({ fromMs: mark.atMs, toMs: endMs, cpuMs: (cpu.user + cpu.system) / 1000, gc: pauses.map((p, i) => [p.startTime, p.duration, kinds[i]]), rooms: logs.map((l) => ({ id: l.room.id, starts: l.startsMs.values(), late: l.lateMs.values(), cpuAt: l.cpuAtStartMs.values(), wall: l.wallMs.values(), cpu: l.cpuMs.values() })) }));
  }
  return {
    seconds,
    cpuMs: (cpu.user + cpu.system) / 1000,
    cpuShare: (cpu.user + cpu.system) / 1e6 / seconds,
    gc: mainGc,
    // The GC of the threads the rooms tick on: the main thread's, or the room workers' (merged).
    roomThreadsGc: roomWorkers > 0 ? gcSummary(mark.atMs, endMs, workerGcPauses(mark.atMs, endMs)) : mainGc,
    snapshotsSent: now.sent - mark.sent,
    snapshotsSkipped: now.skipped - mark.skipped,
    ticksSkipped: now.ticksSkipped - mark.ticksSkipped,
    messagesReceived: now.messagesIn - mark.messagesIn,
    bytesReceived: now.bytesIn - mark.bytesIn,
    bytesSent: now.bytesOut - mark.bytesOut,
    mainThreadCpuMs: (mainCpu.user + mainCpu.system) / 1000,
    roomWorkers,
    rooms: roomWorkers > 0 ? inWorkers : logs
      .filter((l) => l.startsMs.length > 0 || l.room.clientCount > 0)
      .map((l) => {
        const starts = l.startsMs.values();
        const gap = maxGap(starts);
        return {
          id: l.room.id,
          clients: l.room.clientCount,
          bodies: l.room.info().bodies,
          ticks: starts.length,
          cpuMsTotal: round(l.cpuMs.values().reduce((s, v) => s + v, 0), 3),
          tickWallMs: summary(l.wallMs.values()),
          tickCpuMs: summary(l.cpuMs.values()),
          maxGapMs: gap === null ? null : round(gap, 3),
        };
      }),
  };
}

const say = (obj: unknown): void => void process.stdout.write(`${JSON.stringify(obj)}\n`);
const lines = createInterface({ input: process.stdin });
lines.on('line', (line) => {
  void (async () => {
    try {
      const [cmd, arg] = line.trim().split(/\s+/);
      if (cmd === 'rooms') say({ rooms: await openRooms(Number(arg)) });
      else if (cmd === 'mark') {
        for (const l of logs) for (const column of [l.startsMs, l.lateMs, l.cpuAtStartMs, l.wallMs, l.cpuMs]) column.clear();
        pauses.length = 0;
        kinds.length = 0;
        ticksAtMark = new Map(server.game.rooms.list().map((r) => [r.id, r.tick]));
        if (process.env.BENCH_HEAP_PROF) await heapSampling('HeapProfiler.startSampling', { samplingInterval: 4096, includeObjectsCollectedByMajorGC: !process.env.BENCH_HEAP_PROF_LIVE, includeObjectsCollectedByMinorGC: !process.env.BENCH_HEAP_PROF_LIVE });
        mark = { atMs: performance.now(), cpu: process.cpuUsage(), mainCpu: process.threadCpuUsage(), ...(await counters()) };
        say({ marked: true });
      } else if (cmd === 'report') say({ report: await report() });
    } catch (error) {
      say({ error: error instanceof Error ? error.message : String(error) });
    }
  })();
});
const stop = (): void => {
  gcObserver.disconnect();
  void server.close('bench done').then(() => process.exit(0));
};
lines.on('close', stop);
process.on('SIGTERM', stop);
say({ wsUrl: server.wsUrl });
