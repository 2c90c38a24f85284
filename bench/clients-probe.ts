// Investigation probe for the clients-per-core figure: one window of N light bots in the default room of a scene on
// the pinned bench server (CPU 0; bots on CPU 1), with Node/V8 flags of your choice on the server only (e.g.
// --cpu-prof --cpu-prof-dir=DIR), printing the server's CPU per client per tick beside the room's pace.
// Run: node bench/clients-probe.ts CLIENTS [crowd-arena|shape-rain] [WINDOW_MS] [-- SERVER_NODE_FLAGS…]
import { readFileSync } from 'node:fs';
import { fileURLToPath } from 'node:url';
import { nextJson, startNode } from './lib/child.ts';
import { measureWindow, startProbeServer } from './lib/probe-window.ts';
import { CROWD_SCENE, STOCK_SCENE } from './lib/scenes.ts';

const dash = process.argv.indexOf('--');
const args = process.argv.slice(2, dash < 0 ? undefined : dash);
const flags = dash < 0 ? [] : process.argv.slice(dash + 1);
const clients = Number(args[0] ?? 448);
const scene = (args[1] ?? 'crowd-arena') === 'shape-rain' ? STOCK_SCENE : CROWD_SCENE;
const windowMs = Number(args[2] ?? 10000);
const settleMs = Number(process.env.PROBE_SETTLE_MS ?? 4000);
const SWARM = fileURLToPath(new URL('procs/light-swarm.ts', import.meta.url));

const probe = await startProbeServer(flags, [scene.scenario, JSON.stringify(scene.params), '30', String(clients), '0']);
const swarm = startNode(SWARM, [probe.wsUrl, String(clients), String(settleMs), String(windowMs), '0'], { cpu: 1 });
await nextJson(swarm, 'ready', 60_000 + clients * 200);
await nextJson(swarm, 'window', 90_000);
const { bots, server: s, cpu0Busy } = await measureWindow(probe, swarm, windowMs);
const room = s.rooms.reduce((a, b) => (b.clients > a.clients ? b : a));
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
    cpu0Busy: +cpu0Busy.toFixed(3),
    loadavg: readFileSync('/proc/loadavg', 'utf8').trim(),
  })}\n`,
);
