// Investigation probe for the clients-per-core figure: one window of N light bots in the default room of a scene on
// the pinned bench server (CPU 0; bots on CPU 1), with Node/V8 flags of your choice on the server only (e.g.
// --cpu-prof --cpu-prof-dir=DIR), printing the server's CPU per client per tick beside the room's pace.
// Run: node bench/clients-probe.ts CLIENTS [crowd-arena|shape-rain] [WINDOW_MS] [-- SERVER_NODE_FLAGS…]
import { spawn } from 'node:child_process';
import { readFileSync } from 'node:fs';
import { fileURLToPath } from 'node:url';
import { nextJson, sendLine, startNode, stopChild, REPO_ROOT, type Child } from './lib/child.ts';
import { CROWD_SCENE, STOCK_SCENE } from './lib/scenes.ts';
import type { ServerReport, SwarmReport } from './lib/server-bench.ts';

const dash = process.argv.indexOf('--');
const args = process.argv.slice(2, dash < 0 ? undefined : dash);
const flags = dash < 0 ? [] : process.argv.slice(dash + 1);
const clients = Number(args[0] ?? 448);
const scene = (args[1] ?? 'crowd-arena') === 'shape-rain' ? STOCK_SCENE : CROWD_SCENE;
const windowMs = Number(args[2] ?? 10000);
const settleMs = Number(process.env.PROBE_SETTLE_MS ?? 4000);
const SERVER = fileURLToPath(new URL('procs/bench-server.ts', import.meta.url));
const SWARM = fileURLToPath(new URL('procs/light-swarm.ts', import.meta.url));

const proc = spawn('taskset', ['-c', '0', process.execPath, ...flags, SERVER, scene.scenario, JSON.stringify(scene.params), '30', String(clients), '0'], { cwd: REPO_ROOT, stdio: ['pipe', 'pipe', 'inherit'], env: process.env });
let out = '';
proc.stdout.setEncoding('utf8').on('data', (d: string) => (out += d));
const exited = new Promise<number | null>((r) => proc.on('exit', (c) => r(c)));
const server: Child = { proc, stdout: () => out, stderr: () => '', exited };
const wsUrl = await nextJson<string>(server, 'wsUrl', 60_000);
const swarm = startNode(SWARM, [wsUrl, String(clients), String(settleMs), String(windowMs), '0'], { cpu: 1 });
await nextJson(swarm, 'ready', 60_000 + clients * 200);
await nextJson(swarm, 'window', 90_000);
const cpu0 = (): number[] => (readFileSync('/proc/stat', 'utf8').split('\n').find((l) => l.startsWith('cpu0 ')) ?? '').trim().split(/\s+/).slice(1).map(Number);
const stat0 = cpu0();
sendLine(server, 'mark');
await nextJson(server, 'marked', 30_000);
const bots = await nextJson<SwarmReport>(swarm, 'report', windowMs + 30_000);
const stat1 = cpu0();
sendLine(server, 'report');
const s = await nextJson<ServerReport>(server, 'report', 30_000);
await stopChild(swarm);
proc.stdin.end();
await exited;
const room = s.rooms.reduce((a, b) => (b.clients > a.clients ? b : a));
const d = stat1.map((v, i) => v - stat0[i]);
const all = d.reduce((a, b) => a + b, 0);
process.stdout.write(
  `${JSON.stringify({
    clients,
    scene: scene.label,
    cpuShare: +s.cpuShare.toFixed(3),
    ticksPerSecond: +(room.ticks / s.seconds).toFixed(2),
    cpuMsPerTick: +(s.cpuMs / room.ticks).toFixed(3),
    usPerClientTick: +((s.cpuMs * 1000) / room.ticks / clients).toFixed(2),
    tickWallMs: room.tickWallMs,
    tickCpuMs: room.tickCpuMs,
    gc: s.gc,
    messagesPerClientPerTick: +(s.messagesReceived / room.ticks / clients).toFixed(3),
    botsCpu: bots.cpuShare,
    cpu0Busy: +((all - d[3] - d[4]) / all).toFixed(3),
    loadavg: readFileSync('/proc/loadavg', 'utf8').trim(),
  })}\n`,
);
