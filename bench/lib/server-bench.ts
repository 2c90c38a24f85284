// Drives the instrumented server process (procs/bench-server.ts) against a bot swarm in another process: the server
// pinned to one CPU and the bots to another where taskset allows, one measurement window per swarm, reports parsed.
import { cpus } from 'node:os';
import { fileURLToPath } from 'node:url';
import { canPin, nextJson, sendLine, startNode, stopChild, type Child } from './child.ts';
import type { Scene } from './scenes.ts';

const SERVER = fileURLToPath(new URL('../procs/bench-server.ts', import.meta.url));
const SWARMS = {
  light: fileURLToPath(new URL('../procs/light-swarm.ts', import.meta.url)),
  real: fileURLToPath(new URL('../procs/bot-swarm.ts', import.meta.url)),
} as const;

/** Longest the light swarm waits for its rooms to run the settle's ticks (procs/light-swarm.ts). */
const SWARM_SETTLE_LIMIT_MS = 60_000;

/** Which swarm: the light one (protocol-exact, snapshots not decoded) or client-library players. */
export type SwarmKind = keyof typeof SWARMS;

/** A tick-time summary from the server (ms). */
export interface TickSummary {
  p50: number;
  p99: number;
  max: number;
}

/** One room in a server report. */
export interface RoomReport {
  id: string;
  clients: number;
  bodies: number;
  ticks: number;
  cpuMsTotal: number;
  tickWallMs: TickSummary | null;
  tickCpuMs: TickSummary | null;
  maxGapMs: number | null;
}

/** GC pauses of one window (ms): count, total, longest, and the p99 of the pause time per tick-length interval. */
export interface GcSummary {
  pauses: number;
  totalMs: number;
  maxMs: number;
  perTickP99Ms: number;
  /** Full (mark-compact) collections among them and the longest (null where the kind is not reported). */
  majorPauses: number | null;
  majorMaxMs: number | null;
}

/** The server's view of one window. */
export interface ServerReport {
  seconds: number;
  /** The server process's own CPU time in the window (every thread: main, GC helpers, libuv). */
  cpuMs: number;
  cpuShare: number;
  /** The main thread's GC pauses in the window. */
  gc: GcSummary;
  /** GC pauses of the threads the rooms tick on (the main thread's, or the room workers' merged). */
  roomThreadsGc: GcSummary;
  snapshotsSent: number;
  snapshotsSkipped: number;
  ticksSkipped: number;
  messagesReceived: number;
  bytesReceived: number;
  bytesSent: number;
  rooms: RoomReport[];
  /** The main thread's own CPU time in the window (ms): with room workers, the socket and session work alone. */
  mainThreadCpuMs: number;
  /** Room workers the server ran (0: rooms on the main thread). */
  roomWorkers: number;
}

/** The bots' view of one window. */
export interface SwarmReport {
  clients: number;
  seconds: number;
  snapshotsPerClientPerSecond: number;
  kbpsPerClient: number;
  kbpsUpPerClient: number;
  closedClients: number;
  protocolErrors: number;
  cpuShare: number;
  /** How long the light swarm's settle took (ms; longer than asked when the rooms ran below 60 ticks/s). */
  settledMs?: number;
  /** The light swarm's own event-loop delay in the window (ms); absent for the client-library swarm. */
  loopDelayMs?: { p99: number; max: number };
  /** Each room's snapshots as the light swarm's bots saw them (rooms r1…rN; empty in the default room). */
  rooms?: Array<{ id: string; snapshots: number; maxArrivalGapMs: number; maxTickStep: number }>;
}

/** A running server process. */
export interface BenchServer {
  child: Child;
  wsUrl: string;
  /** CPUs the server and the bots are pinned to; null when unpinned (no taskset, or one CPU). */
  pinning: { server: number; bots: number } | null;
}

/**
 * Starts the server process on a scene (pinned to CPU 0 when taskset and a second CPU exist), its rooms on the main
 * thread or in `roomWorkers` worker threads (pinned with it: the figure is per core).
 */
export async function startBenchServer(scene: Scene, snapshotRateHz: number, maxClients: number, roomWorkers = 0): Promise<BenchServer> {
  const pinning = cpus().length >= 2 && canPin() ? { server: 0, bots: 1 } : null;
  const child = startNode(SERVER, [scene.scenario, JSON.stringify(scene.params), String(snapshotRateHz), String(maxClients), String(roomWorkers)], { stdin: true, cpu: pinning?.server });
  const wsUrl = await nextJson<string>(child, 'wsUrl', 60_000);
  return { child, wsUrl, pinning };
}

/** Opens rooms r1…rN of the server's scene (rooms already open are kept). */
export async function openRooms(server: BenchServer, n: number): Promise<string[]> {
  sendLine(server.child, `rooms ${n}`);
  return nextJson<string[]>(server.child, 'rooms', 60_000 + n * 2000);
}

/** Runs one swarm of `clients` bots (spread over rooms r1…rN when `rooms` > 0): settle, then one measured window. */
export async function measureWindow(server: BenchServer, kind: SwarmKind, clients: number, settleMs: number, windowMs: number, rooms = 0): Promise<{ server: ServerReport; bots: SwarmReport }> {
  const args = [server.wsUrl, String(clients), String(settleMs), String(windowMs), ...(kind === 'light' ? [String(rooms)] : [])];
  if (kind === 'real' && rooms > 0) throw new Error('measureWindow: the client-library swarm only joins the default room');
  const swarm = startNode(SWARMS[kind], args, { cpu: server.pinning?.bots });
  try {
    await nextJson<number>(swarm, 'ready', 60_000 + clients * 200);
    await nextJson<boolean>(swarm, 'window', Math.max(settleMs, SWARM_SETTLE_LIMIT_MS) + 30_000);
    sendLine(server.child, 'mark');
    await nextJson<boolean>(server.child, 'marked', 30_000);
    const bots = await nextJson<SwarmReport>(swarm, 'report', windowMs + 30_000);
    sendLine(server.child, 'report');
    return { server: await nextJson<ServerReport>(server.child, 'report', 30_000), bots };
  } finally {
    await stopChild(swarm);
  }
}

/** Stops the server process. */
export async function stopBenchServer(server: BenchServer): Promise<void> {
  await stopChild(server.child);
}
