// Investigation probe for the rooms-per-core figure: one window of R shape-rain 300 rooms (4 light bots each) on the
// pinned bench server, with Node/V8 flags of your choice on the server only (e.g. --cpu-prof, --trace-gc), and every
// room tick and GC pause of the window dumped for a look at what each long gap between tick starts held.
// Run: node bench/rooms-probe.ts ROOMS [WORKERS] [WINDOW_MS] [-- SERVER_NODE_FLAGS…]   (dump: BENCH_DUMP=FILE)
import { writeFileSync } from 'node:fs';
import { fileURLToPath } from 'node:url';
import { nextJson, sendLine, startNode } from './lib/child.ts';
import { measureWindow, startProbeServer } from './lib/probe-window.ts';
import { STOCK_SCENE } from './lib/scenes.ts';

const dash = process.argv.indexOf('--');
const args = process.argv.slice(2, dash < 0 ? undefined : dash);
const flags = dash < 0 ? [] : process.argv.slice(dash + 1);
const rooms = Number(args[0] ?? 8);
const workers = Number(args[1] ?? 0);
const windowMs = Number(args[2] ?? 10000);
const settleMs = Number(process.env.PROBE_SETTLE_MS ?? 4000);
const SWARM = fileURLToPath(new URL('procs/light-swarm.ts', import.meta.url));

const probe = await startProbeServer(flags, [STOCK_SCENE.scenario, JSON.stringify(STOCK_SCENE.params), '30', String(rooms * 4), String(workers)]);
const { server, wsUrl } = probe;
sendLine(server, `rooms ${rooms}`);
await nextJson(server, 'rooms', 120_000);
const swarm = startNode(SWARM, [wsUrl, String(rooms * 4), String(settleMs), String(windowMs), String(rooms)], { cpu: 1, env: { BENCH_DUMP: '' } });
await nextJson(swarm, 'ready', 60_000);
await nextJson(swarm, 'window', 90_000);
const { bots, server: s, cpu0Busy } = await measureWindow(probe, swarm, windowMs);
if (process.env.PROBE_SERVER_OUT) writeFileSync(process.env.PROBE_SERVER_OUT, probe.stdout());
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
    cpu0Busy: +cpu0Busy.toFixed(3),
  })}\n`,
);
