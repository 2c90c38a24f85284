// Investigation probe for the rooms-per-core figure: one window of R shape-rain 300 rooms (4 light bots each) on the
// pinned bench server, with Node/V8 flags of your choice on the server only (e.g. --cpu-prof, --trace-gc), and every
// room tick and GC pause of the window dumped for a look at what each long gap between tick starts held.
// Run: node bench/rooms-probe.ts ROOMS [WORKERS] [WINDOW_MS] [-- SERVER_NODE_FLAGS…]   (dump: BENCH_DUMP=FILE)
import { spawn } from 'node:child_process';
import { createRequire } from 'node:module';
import { fileURLToPath } from 'node:url';
import { nextJson, sendLine, startNode, stopChild, REPO_ROOT, type Child } from './lib/child.ts';
import { STOCK_SCENE } from './lib/scenes.ts';
import type { ServerReport, SwarmReport } from './lib/server-bench.ts';

const require0 = createRequire(import.meta.url);
const dash = process.argv.indexOf('--');
const args = process.argv.slice(2, dash < 0 ? undefined : dash);
const flags = dash < 0 ? [] : process.argv.slice(dash + 1);
const rooms = Number(args[0] ?? 8);
const workers = Number(args[1] ?? 0);
const windowMs = Number(args[2] ?? 10000);
const settleMs = Number(process.env.PROBE_SETTLE_MS ?? 4000);
const SERVER = fileURLToPath(new URL('procs/bench-server.ts', import.meta.url));
const SWARM = fileURLToPath(new URL('procs/light-swarm.ts', import.meta.url));

const proc = spawn('taskset', ['-c', '0', process.execPath, ...flags, SERVER, STOCK_SCENE.scenario, JSON.stringify(STOCK_SCENE.params), '30', String(rooms * 4), String(workers)], { cwd: REPO_ROOT, stdio: ['pipe', 'pipe', 'inherit'], env: process.env });
let out = '';
proc.stdout.setEncoding('utf8').on('data', (d: string) => (out += d));
const exited = new Promise<number | null>((r) => proc.on('exit', (c) => r(c)));
const server: Child = { proc, stdout: () => out, stderr: () => '', exited };
const wsUrl = await nextJson<string>(server, 'wsUrl', 60_000);
sendLine(server, `rooms ${rooms}`);
await nextJson(server, 'rooms', 120_000);
const swarm = startNode(SWARM, [wsUrl, String(rooms * 4), String(settleMs), String(windowMs), String(rooms)], { cpu: 1, env: { BENCH_DUMP: '' } });
await nextJson(swarm, 'ready', 60_000);
await nextJson(swarm, 'window', 90_000);
const cpu0 = (): number[] => (require0('node:fs').readFileSync('/proc/stat', 'utf8').split('\n').find((l: string) => l.startsWith('cpu0 ')) ?? '').trim().split(/\s+/).slice(1).map(Number);
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
if (process.env.PROBE_SERVER_OUT) (await import('node:fs')).writeFileSync(process.env.PROBE_SERVER_OUT, out);
const measured = s.rooms.filter((x) => /^r\d+$/.test(x.id));
const ticks = measured.reduce((a, x) => a + x.ticks, 0);
process.stdout.write(
  `${JSON.stringify({
    rooms,
    workers,
    cpuShare: +s.cpuShare.toFixed(3),
    usPerRoomTick: +((s.cpuMs * 1000) / ticks).toFixed(1),
    mainThreadCpuShare: +(s.mainThreadCpuMs / 1000 / s.seconds).toFixed(3),
    worstGapMs: Math.max(...measured.map((x) => x.maxGapMs ?? Infinity)),
    minTicksPerSecond: Math.min(...measured.map((x) => x.ticks)) / s.seconds,
    tickWallP99: Math.max(...measured.map((x) => x.tickWallMs?.p99 ?? 0)),
    tickCpuP50: measured.map((x) => x.tickCpuMs?.p50 ?? 0).sort()[measured.length >> 1],
    gc: s.roomThreadsGc,
    clientGapMs: Math.max(...(bots.rooms ?? []).map((x) => x.maxArrivalGapMs)),
    botsCpu: bots.cpuShare,
    slowdownTicks: s.ticksSkipped,
    /** CPU 0 (the server's) busy share over the window, everyone's work together (from /proc/stat). */
    cpu0Busy: +(() => { const d = stat1.map((v, i) => v - stat0[i]); const all = d.reduce((a, b) => a + b, 0); return (all - d[3] - d[4]) / all; })().toFixed(3),
  })}\n`,
);
