// Rooms per core: one server process (pinned to one CPU) runs R rooms of the stock shape-rain 300 scene on its one
// event loop, 4 light bots in each (the swarm pinned to the other CPU). R climbs a ladder; a count passes when no
// room's tick starts were more than 2 ticks apart and every room kept 60 ticks/s. The figure is the largest passing R.
// The same ladder with the rooms in room workers (pinned to the same one CPU) is rooms-per-core-workers.ts.
import type { FigureImpl, FigureOutput, ReportRow } from '../lib/figure.ts';
import { judgeRoomsWindow, ladderResult, MAX_ROOM_TICK_GAP_TICKS, nextLadderCount, TICK_BUDGET_MS } from '../lib/rules.ts';
import { STOCK_SCENE } from '../lib/scenes.ts';
import { measureWindow, openRooms, startBenchServer, stopBenchServer } from '../lib/server-bench.ts';
import { round } from '../lib/stats.ts';

const GOAL = 20;
const BOTS_PER_ROOM = 4;
const SNAPSHOT_RATE_HZ = 30;
/** Rooms of the extra window that measures the main thread's CPU per client when the ladder stopped below it. */
const CPU_PROBE_ROOMS = 12;

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
  serverCpuShare: number;
  botCpuShare: number;
  gcPerTickP99Ms: number;
  gcMaxMs: number;
  slowdownTicks: number;
  /** The main thread's CPU per client per tick (µs): with room workers, socket and session work alone. */
  mainThreadUsPerClientTick: number;
}

/** Runs the rooms ladder with the rooms on the main thread (roomWorkers 0) or in that many room workers. */
export async function runRoomsLadder(opts: { quick: boolean; log(m: string): void }, roomWorkers: number): Promise<FigureOutput> {
  const where = roomWorkers === 0 ? 'on its one event loop' : `in ${roomWorkers} room worker threads`;
  const key = roomWorkers === 0 ? 'roomsPerCore' : 'roomsPerCoreWorkers';
  const quick = opts.quick;
  const rungs = quick ? [1, 2, 4, 8, 12, 16] : [1, 2, 4, 6, 8, 10, 12, 14, 16, 20, 24];
  const resolution = quick ? 2 : 1;
  const settleMs = quick ? 3000 : 4000;
  const windowMs = quick ? 3000 : 6000;
  const server = await startBenchServer(STOCK_SCENE, SNAPSHOT_RATE_HZ, Math.max(...rungs) * BOTS_PER_ROOM, roomWorkers);
  const steps: RoomsStep[] = [];
  let cpuProbe: RoomsStep | null = null;
  const results = new Map<number, boolean>();
  const measure = async (r: number): Promise<RoomsStep> => {
    const { server: s, bots } = await measureWindow(server, 'light', r * BOTS_PER_ROOM, settleMs, windowMs, r);
    const measured = s.rooms.filter((x) => /^r\d+$/.test(x.id));
    const verdict = judgeRoomsWindow(s.seconds, measured.map((x) => ({ id: x.id, ticks: x.ticks, maxGapMs: x.maxGapMs })));
    if (measured.length !== r) verdict.reasons.push(`${measured.length} of ${r} rooms ticked`);
    if (bots.closedClients > 0) verdict.reasons.push(`${bots.closedClients} clients dropped`);
    const gaps = measured.map((x) => x.maxGapMs ?? Infinity);
    const p99s = measured.map((x) => x.tickWallMs?.p99 ?? Infinity);
    return {
      rooms: r,
      pass: verdict.reasons.length === 0,
      why: verdict.reasons.join('; '),
      worstGapMs: gaps.length > 0 && Number.isFinite(Math.max(...gaps)) ? round(Math.max(...gaps), 2) : null,
      roomsOverGap: gaps.filter((g) => g > MAX_ROOM_TICK_GAP_TICKS * TICK_BUDGET_MS).length,
      minTicksPerSecond: measured.length > 0 ? round(Math.min(...measured.map((x) => x.ticks)) / s.seconds, 1) : 0,
      worstTickP99Ms: p99s.length > 0 && Number.isFinite(Math.max(...p99s)) ? round(Math.max(...p99s), 2) : null,
      serverCpuShare: round(s.cpuShare, 3),
      botCpuShare: round(bots.cpuShare, 3),
      gcPerTickP99Ms: s.gc.perTickP99Ms,
      gcMaxMs: s.gc.maxMs,
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
      opts.log(`${r} room(s): ${step.pass ? 'pass' : `miss (${step.why})`}; worst gap ${step.worstGapMs} ms, server CPU ${step.serverCpuShare}, bots CPU ${step.botCpuShare}`);
    }
    // The main thread's CPU per client wants many clients (its fixed cost spreads thin): one more window at a set count.
    if (roomWorkers > 0 && Math.max(...steps.map((x) => x.rooms)) < CPU_PROBE_ROOMS) {
      await openRooms(server, CPU_PROBE_ROOMS);
      const probe = await measure(CPU_PROBE_ROOMS);
      opts.log(`${CPU_PROBE_ROOMS} rooms (main-thread CPU probe): ${probe.mainThreadUsPerClientTick} µs per client per tick on the main thread`);
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
  const rows: ReportRow[] = [{ figure: figureName, measure: `largest room count without a tick gap > ${MAX_ROOM_TICK_GAP_TICKS} ticks (${STOCK_SCENE.label}, ${BOTS_PER_ROOM} bots each, rooms ${where}${quick ? ', coarse' : ''})`, value: best, unit: '', digits: 0, goal: { op: '>=', value: GOAL } }];
  // A CPU-time figure, so it holds on a loaded machine: taken at the largest room count measured, passing or not.
  const largest = cpuProbe ?? steps.reduce<RoomsStep | null>((a, x) => (a === null || x.rooms >= a.rooms ? x : a), null);
  if (roomWorkers > 0 && largest) rows.push({ figure: figureName, measure: `main thread CPU per client per tick at ${largest.rooms} rooms × ${BOTS_PER_ROOM} bots (sockets and sessions only)`, value: largest.mainThreadUsPerClientTick, unit: 'µs', digits: 1 });
  if (firstMiss) rows.push({ figure: figureName, measure: `first miss at ${firstMiss.rooms} rooms: worst tick gap (${firstMiss.why})`, value: firstMiss.worstGapMs, unit: 'ms', digits: 1 });
  return {
    headline: roomWorkers === 0 ? { [key]: best } : { [key]: best, mainThreadUsPerClientTick: largest?.mainThreadUsPerClientTick ?? null },
    detail: { roomWorkers, cpuProbe, scene: STOCK_SCENE, botsPerRoom: BOTS_PER_ROOM, snapshotRateHz: SNAPSHOT_RATE_HZ, pinning: server.pinning, ladder: rungs, settleMs, windowMs, maxGapMs: round(MAX_ROOM_TICK_GAP_TICKS * TICK_BUDGET_MS, 2), steps },
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
      `A count passes when every room's tick starts were at most ${MAX_ROOM_TICK_GAP_TICKS} ticks (${(MAX_ROOM_TICK_GAP_TICKS * TICK_BUDGET_MS).toFixed(1)} ms) apart over the ${windowMs} ms window, every room ran ≥ 99% of 60 ticks/s and no client was dropped${quick ? '' : '; a miss is retried once'}. After the first miss the search halves the interval down to ${resolution} room(s). Per-step GC pause per tick (p99) and the longest pause are in detail.steps.`,
    ],
  };
}

/** The rooms-per-core figure: every room on the server's main thread. */
export const figure: FigureImpl = { run: (opts) => runRoomsLadder(opts, 0) };
