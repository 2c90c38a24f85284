// Rooms per core: one server process (pinned to one CPU) runs R rooms of the stock shape-rain 300 scene on its one
// event loop, 4 light bots in each (the swarm pinned to the other CPU, its own CPU and loop delay reported). R climbs
// a ladder; a count holds when every room kept 60 ticks/s with tick p99 < 16.7 ms and tick starts ≤ 2 ticks apart,
// and its clients saw every snapshot with no wait over the spacing plus 2 ticks (bench/lib/rules.ts). The figure is
// the largest holding R, beside the server's CPU per room tick. The same ladder with the rooms in room workers
// (pinned to the same one CPU) is rooms-per-core-workers.ts.
import type { FigureImpl, FigureOutput, ReportRow } from '../lib/figure.ts';
import { judgeRoomsWindow, ladderResult, MAX_ROOM_TICK_GAP_TICKS, maxClientGapMs, nextLadderCount, TICK_BUDGET_MS, TICK_RATE_HZ, type RoomWindow } from '../lib/rules.ts';
import { STOCK_SCENE } from '../lib/scenes.ts';
import { measureWindow, openRooms, startBenchServer, stopBenchServer } from '../lib/server-bench.ts';
import { round } from '../lib/stats.ts';

const GOAL = 20;
const BOTS_PER_ROOM = 4;
const SNAPSHOT_RATE_HZ = 30;
const SNAPSHOT_INTERVAL_TICKS = TICK_RATE_HZ / SNAPSHOT_RATE_HZ;
/**
 * Rooms of the extra window that measures CPU per room tick (and, with workers, the main thread's CPU per client) when
 * the ladder stopped below it: the goal's count, so the CPU figures describe the load the goal asks for.
 */
const CPU_PROBE_ROOMS = GOAL;

interface RoomsStep {
  rooms: number;
  pass: boolean;
  why: string;
  /** The worst room's longest gap between tick starts (ms). */
  worstGapMs: number | null;
  /** Rooms whose longest gap exceeded 2 ticks. */
  roomsOverGap: number;
  minTicksPerSecond: number;
  worstTickP99Ms: number | null;
  /** The longest wait between two snapshots at any client (ms), and the largest tick step between them. */
  worstClientGapMs: number | null;
  worstClientTickStep: number | null;
  serverCpuShare: number;
  /** The server process's CPU time per room tick (µs): every thread, sockets included. */
  serverUsPerRoomTick: number;
  botCpuShare: number;
  /** The bots' own event-loop delay (ms): when high, the bots (not the server) were late. */
  botLoopDelayP99Ms: number | null;
  botLoopDelayMaxMs: number | null;
  /** How long the step's settle took (ms): it waits for the rooms to run the settle's worth of ticks. */
  settledMs: number | null;
  /** GC of the threads the rooms tick on (the main thread, or the room workers merged). */
  gcPerTickP99Ms: number;
  gcMaxMs: number;
  gcTotalMs: number;
  slowdownTicks: number;
  /** The main thread's CPU per client per tick (µs): with room workers, socket and session work alone. */
  mainThreadUsPerClientTick: number;
}

/** The worst of some optional figures (null when none was measured). */
function worst(xs: ReadonlyArray<number | null>): number | null {
  const known = xs.filter((x): x is number => x !== null && Number.isFinite(x));
  return known.length > 0 ? round(Math.max(...known), 2) : null;
}

/** Runs the rooms ladder with the rooms on the main thread (roomWorkers 0) or in that many room workers. */
export async function runRoomsLadder(opts: { quick: boolean; log(m: string): void }, roomWorkers: number): Promise<FigureOutput> {
  const where = roomWorkers === 0 ? 'on its one event loop' : `in ${roomWorkers} room worker threads`;
  const key = roomWorkers === 0 ? 'roomsPerCore' : 'roomsPerCoreWorkers';
  const quick = opts.quick;
  const rungs = quick ? [1, 4, 8, 12, 16, 20] : [1, 4, 8, 12, 16, 20, 24, 28];
  const resolution = quick ? 2 : 1;
  const settleMs = quick ? 3000 : 4000;
  // Worker rooms' tick p99 and longest gap come from their last 600 ticks: a 10 s window makes those the window's.
  const windowMs = quick ? 5000 : 10000;
  const server = await startBenchServer(STOCK_SCENE, SNAPSHOT_RATE_HZ, Math.max(...rungs) * BOTS_PER_ROOM, roomWorkers);
  const steps: RoomsStep[] = [];
  let cpuProbe: RoomsStep | null = null;
  const results = new Map<number, boolean>();
  const measure = async (r: number): Promise<RoomsStep> => {
    const { server: s, bots } = await measureWindow(server, 'light', r * BOTS_PER_ROOM, settleMs, windowMs, r);
    // Rooms r1…rR only: rooms of a larger earlier step are open but empty (paused).
    const measured = s.rooms.filter((x) => /^r\d+$/.test(x.id) && Number(x.id.slice(1)) <= r);
    const seen = new Map((bots.rooms ?? []).map((x) => [x.id, x]));
    const windows: RoomWindow[] = measured.map((x) => {
      const c = seen.get(x.id);
      return { id: x.id, ticks: x.ticks, maxGapMs: x.maxGapMs, tickP99Ms: x.tickWallMs?.p99 ?? null, clients: x.clients, snapshots: c?.snapshots ?? 0, clientGapMs: c && c.snapshots > 1 ? c.maxArrivalGapMs : null, clientTickStep: c && c.snapshots > 1 ? c.maxTickStep : null };
    });
    const verdict = judgeRoomsWindow(s.seconds, windows, { botsPerRoom: BOTS_PER_ROOM, snapshotIntervalTicks: SNAPSHOT_INTERVAL_TICKS });
    if (measured.length !== r) verdict.reasons.push(`${measured.length} of ${r} rooms ticked`);
    if (bots.closedClients > 0) verdict.reasons.push(`${bots.closedClients} clients dropped`);
    const roomTicks = measured.reduce((sum, x) => sum + x.ticks, 0);
    return {
      rooms: r,
      pass: verdict.reasons.length === 0,
      why: verdict.reasons.join('; '),
      worstGapMs: worst(measured.map((x) => x.maxGapMs ?? Infinity)),
      roomsOverGap: measured.filter((x) => !(x.maxGapMs !== null && x.maxGapMs <= MAX_ROOM_TICK_GAP_TICKS * TICK_BUDGET_MS)).length,
      minTicksPerSecond: measured.length > 0 ? round(Math.min(...measured.map((x) => x.ticks)) / s.seconds, 1) : 0,
      worstTickP99Ms: worst(measured.map((x) => x.tickWallMs?.p99 ?? null)),
      worstClientGapMs: worst(windows.map((x) => x.clientGapMs)),
      worstClientTickStep: worst(windows.map((x) => x.clientTickStep)),
      serverCpuShare: round(s.cpuShare, 3),
      serverUsPerRoomTick: roomTicks > 0 ? round((s.cpuMs * 1000) / roomTicks, 1) : 0,
      botCpuShare: round(bots.cpuShare, 3),
      botLoopDelayP99Ms: bots.loopDelayMs ? round(bots.loopDelayMs.p99, 2) : null,
      botLoopDelayMaxMs: bots.loopDelayMs ? round(bots.loopDelayMs.max, 2) : null,
      settledMs: bots.settledMs === undefined ? null : Math.round(bots.settledMs),
      gcPerTickP99Ms: s.roomThreadsGc.perTickP99Ms,
      gcMaxMs: s.roomThreadsGc.maxMs,
      gcTotalMs: s.roomThreadsGc.totalMs,
      slowdownTicks: s.ticksSkipped,
      mainThreadUsPerClientTick: round((s.mainThreadCpuMs * 1000) / (r * BOTS_PER_ROOM * s.seconds * 60), 2),
    };
  };
  try {
    for (let r = nextLadderCount(rungs, results, resolution); r !== null; r = nextLadderCount(rungs, results, resolution)) {
      await openRooms(server, r);
      opts.log(`${r} room(s) × ${BOTS_PER_ROOM} light bots: ${settleMs} ms settle, ${windowMs} ms window`);
      let step = await measure(r);
      if (!step.pass && !quick) {
        opts.log(`${r} room(s) missed (${step.why}); retrying once`);
        steps.push(step);
        step = await measure(r);
      }
      steps.push(step);
      results.set(r, step.pass);
      opts.log(`${r} room(s): ${step.pass ? 'pass' : `miss (${step.why})`}; worst tick gap ${step.worstGapMs} ms, client gap ${step.worstClientGapMs} ms, tick p99 ${step.worstTickP99Ms} ms, server CPU ${step.serverCpuShare} (${step.serverUsPerRoomTick} µs per room tick), GC p99/max ${step.gcPerTickP99Ms}/${step.gcMaxMs} ms, bots CPU ${step.botCpuShare} (loop delay max ${step.botLoopDelayMaxMs} ms)`);
    }
    // CPU per room tick and per client want many rooms (the process's fixed cost spreads thin): one more window at the goal.
    if (Math.max(...steps.map((x) => x.rooms)) < CPU_PROBE_ROOMS) {
      await openRooms(server, CPU_PROBE_ROOMS);
      const probe = await measure(CPU_PROBE_ROOMS);
      opts.log(`${CPU_PROBE_ROOMS} rooms (CPU probe, ${probe.pass ? 'held' : `not held: ${probe.why}`}): ${probe.serverUsPerRoomTick} µs of server CPU per room tick, GC per tick p99 ${probe.gcPerTickP99Ms} ms, main thread ${probe.mainThreadUsPerClientTick} µs per client per tick`);
      cpuProbe = probe;
    }
  } finally {
    await stopBenchServer(server);
  }
  const best = ladderResult(results);
  // The first count whose final verdict (after any retry) was a miss, and its last window.
  const missed = [...results].filter(([, pass]) => !pass).map(([n]) => n);
  const firstMiss = missed.length > 0 ? (steps.filter((x) => x.rooms === Math.min(...missed)).at(-1) ?? null) : null;
  const figureName = roomWorkers === 0 ? 'rooms per core' : 'rooms per core, workers';
  const rows: ReportRow[] = [{ figure: figureName, measure: `largest room count held at 60 ticks/s, tick p99 < ${TICK_BUDGET_MS.toFixed(1)} ms, no gap > ${MAX_ROOM_TICK_GAP_TICKS} ticks (${STOCK_SCENE.label}, ${BOTS_PER_ROOM} bots each, rooms ${where}${quick ? ', coarse' : ''})`, value: best, unit: '', digits: 0, goal: { op: '>=', value: GOAL } }];
  // CPU-time figures, so they hold on a loaded machine: taken at the largest room count measured, passing or not.
  const largest = cpuProbe ?? steps.reduce<RoomsStep | null>((a, x) => (a === null || x.rooms >= a.rooms ? x : a), null);
  const usPerRoomTick = largest?.serverUsPerRoomTick ?? null;
  if (largest && usPerRoomTick) {
    rows.push({ figure: figureName, measure: `server CPU per room tick at ${largest.rooms} rooms (every thread, sockets included)`, value: usPerRoomTick, unit: 'µs', digits: 0 });
    rows.push({ figure: figureName, measure: `rooms one core's CPU time could tick at 60 Hz (16.7 ms ÷ CPU per room tick; the wall-clock count above is what held)`, value: Math.floor((TICK_BUDGET_MS * 1000) / usPerRoomTick), unit: '', digits: 0 });
    rows.push({ figure: figureName, measure: `GC pause per tick p99 / longest at ${largest.rooms} rooms (the rooms' threads)`, value: largest.gcPerTickP99Ms, unit: `ms / ${largest.gcMaxMs.toFixed(1)} ms`, digits: 2 });
  }
  const botsBusiest = steps.reduce((m, x) => Math.max(m, x.botCpuShare), 0);
  rows.push({ figure: figureName, measure: 'bots: most CPU of their core in any window (they are not the limit below 1)', value: botsBusiest, unit: 'cores', digits: 2 });
  if (roomWorkers > 0 && largest) rows.push({ figure: figureName, measure: `main thread CPU per client per tick at ${largest.rooms} rooms × ${BOTS_PER_ROOM} bots (sockets and sessions only)`, value: largest.mainThreadUsPerClientTick, unit: 'µs', digits: 1 });
  if (firstMiss) rows.push({ figure: figureName, measure: `first miss at ${firstMiss.rooms} rooms: worst tick gap (${firstMiss.why})`, value: firstMiss.worstGapMs, unit: 'ms', digits: 1 });
  const usKey = roomWorkers === 0 ? 'usPerRoomTick' : 'usPerRoomTickWorkers';
  return {
    headline: roomWorkers === 0 ? { [key]: best, [usKey]: usPerRoomTick } : { [key]: best, [usKey]: usPerRoomTick, mainThreadUsPerClientTick: largest?.mainThreadUsPerClientTick ?? null },
    detail: { roomWorkers, cpuProbe, scene: STOCK_SCENE, botsPerRoom: BOTS_PER_ROOM, snapshotRateHz: SNAPSHOT_RATE_HZ, pinning: server.pinning, ladder: rungs, settleMs, windowMs, maxGapMs: round(MAX_ROOM_TICK_GAP_TICKS * TICK_BUDGET_MS, 2), maxClientGapMs: round(maxClientGapMs(SNAPSHOT_INTERVAL_TICKS), 2), steps },
    rows,
    charts: [
      {
        title: `Rooms per core (rooms ${where}): worst gap between a room's tick starts (${STOCK_SCENE.label}, ${BOTS_PER_ROOM} bots per room)`,
        unit: 'ms',
        goal: MAX_ROOM_TICK_GAP_TICKS * TICK_BUDGET_MS,
        bars: steps.map((x) => ({ label: `${x.rooms} room${x.rooms === 1 ? '' : 's'}${x.pass ? '' : ' (miss)'}`, value: x.worstGapMs, series: x.pass ? ('ours' as const) : ('baseline' as const) })),
      },
    ],
    notes: [
      `One server process (procs/bench-server.ts${server.pinning ? `, pinned to CPU ${server.pinning.server}` : ', not pinned'}) runs rooms r1…rR of ${STOCK_SCENE.label} ${where}, ${SNAPSHOT_RATE_HZ} Hz snapshots; ${BOTS_PER_ROOM} light bots per room (procs/light-swarm.ts${server.pinning ? `, pinned to CPU ${server.pinning.bots}` : ''}; see clients per core for how they match client-library players). Rooms of earlier steps stay open (they pause while empty) and each step settles ${settleMs} ms first, so new rooms' rain has landed.`,
      `A count holds when, over the ${windowMs} ms window, every room r1…rR ran ≥ 99% of 60 ticks/s with tick p99 < ${TICK_BUDGET_MS.toFixed(1)} ms and tick starts at most ${MAX_ROOM_TICK_GAP_TICKS} ticks (${(MAX_ROOM_TICK_GAP_TICKS * TICK_BUDGET_MS).toFixed(1)} ms) apart, held exactly ${BOTS_PER_ROOM} players, and its bots received every snapshot (tick steps of ${SNAPSHOT_INTERVAL_TICKS}) with no wait over ${maxClientGapMs(SNAPSHOT_INTERVAL_TICKS).toFixed(1)} ms (the spacing plus ${MAX_ROOM_TICK_GAP_TICKS} ticks)${quick ? '' : '; a miss is retried once'}. After the first miss the search halves the interval down to ${resolution} room(s). The bots' CPU share and event-loop delay, GC pause per tick (p99) and the longest pause of the rooms' threads, and the server's CPU per room tick are in detail.steps.`,
    ],
  };
}

/** The rooms-per-core figure: every room on the server's main thread. */
export const figure: FigureImpl = { run: (opts) => runRoomsLadder(opts, 0) };
