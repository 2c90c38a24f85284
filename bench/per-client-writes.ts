// Per-client cost of a real server process (issue 14 item 4): the bench server (procs/bench-server.ts, stock
// shape-rain 300, 30 Hz snapshots) under light bots (procs/light-swarm.ts) at two client counts. Per window: the
// server's own CPU time per tick (process.cpuUsage), the messages each client sent per second, and the write system
// calls per socket per tick (/proc/PID/io syscw, Linux). The cost per client per tick is the slope between the two
// counts. With --against DIR (a checkout of another commit, e.g. `git archive main | tar -x -C DIR`, node_modules
// linked), DIR's server and bots run in alternating rounds, so before/after share the machine's load.
// Run: node_modules/.bin/node bench/per-client-writes.ts [--clients 16,96] [--rounds 2] [--window 5000] [--against DIR]
import { readFileSync } from 'node:fs';
import { loadavg } from 'node:os';
import { join, resolve } from 'node:path';
import { pathToFileURL } from 'node:url';
import type * as ServerBench from './lib/server-bench.ts';
import type * as Scenes from './lib/scenes.ts';
import { median, round } from './lib/stats.ts';

const argv = process.argv.slice(2);
const flag = (name: string): string | undefined => {
  const i = argv.indexOf(`--${name}`);
  return i >= 0 ? argv[i + 1] : undefined;
};
const counts = (flag('clients') ?? '16,96').split(',').map(Number);
const rounds = Number(flag('rounds') ?? 2);
const windowMs = Number(flag('window') ?? 5000);
const settleMs = Number(flag('settle') ?? 2000);
const againstDir = flag('against');
if (counts.length !== 2 || !counts.every((n) => Number.isInteger(n) && n > 0) || counts[0] >= counts[1]) throw new Error('--clients takes two counts, low,high');

interface Side {
  name: string;
  bench: typeof ServerBench;
  scene: Scenes.Scene;
}

async function side(name: string, root: string): Promise<Side> {
  const bench = (await import(pathToFileURL(join(root, 'bench/lib/server-bench.ts')).href)) as typeof ServerBench;
  const scenes = (await import(pathToFileURL(join(root, 'bench/lib/scenes.ts')).href)) as typeof Scenes;
  return { name, bench, scene: scenes.STOCK_SCENE };
}

/** Write system calls the process has made so far (Linux /proc; null elsewhere). */
function writeSyscalls(pid: number | undefined): number | null {
  try {
    const m = /^syscw: (\d+)$/m.exec(readFileSync(`/proc/${pid}/io`, 'utf8'));
    return m ? Number(m[1]) : null;
  } catch {
    return null;
  }
}

interface Window {
  clients: number;
  cpuMsPerTick: number;
  ticksPerSecond: number;
  messagesPerClientPerSecond: number;
  writesPerClientPerTick: number | null;
}

async function measure(s: Side, clients: number): Promise<Window> {
  // Room for the warm-up bot, whose player may still be held for a reconnect when the measured swarm joins.
  const server = await s.bench.startBenchServer(s.scene, 30, Math.max(...counts) + 8);
  try {
    await s.bench.measureWindow(server, 'light', 1, 1500, 500); // the rain lands before anything is measured
    const pid = server.child.proc.pid;
    const w0 = writeSyscalls(pid);
    const { server: r } = await s.bench.measureWindow(server, 'light', clients, settleMs, windowMs);
    const w1 = writeSyscalls(pid);
    const ticks = r.rooms.find((room) => room.id === 'default')?.ticks ?? 0;
    // The syscall count spans the settle too: spread it over the settle's ticks as well (60 per second).
    const spanTicks = ticks + (settleMs / 1000) * 60;
    return {
      clients,
      cpuMsPerTick: r.cpuMs / ticks,
      ticksPerSecond: ticks / r.seconds,
      messagesPerClientPerSecond: r.messagesReceived / clients / r.seconds,
      writesPerClientPerTick: w0 === null || w1 === null ? null : (w1 - w0) / clients / spanTicks,
    };
  } finally {
    await s.bench.stopBenchServer(server);
  }
}

const sides = [await side('now', resolve('.'))];
if (againstDir) sides.push(await side(againstDir, resolve(againstDir)));
const results = new Map<string, Window[]>(sides.map((s) => [s.name, []]));
const load0 = loadavg()[0];
for (let r = 0; r < rounds; r++) {
  for (let k = 0; k < sides.length; k++) {
    const s = sides[(k + r) % sides.length];
    for (const n of counts) {
      const w = await measure(s, n);
      results.get(s.name)!.push(w);
      console.error(`round ${r + 1} ${s.name} ${n} clients: ${w.cpuMsPerTick.toFixed(3)} ms CPU/tick, ${w.ticksPerSecond.toFixed(1)} ticks/s, ${w.messagesPerClientPerSecond.toFixed(1)} msg/client/s, ${w.writesPerClientPerTick?.toFixed(2) ?? '?'} writes/client/tick`);
    }
  }
}
const summary = sides.map((s) => {
  const ws = results.get(s.name)!;
  const at = (n: number, key: keyof Window): number => median(ws.filter((w) => w.clients === n).map((w) => w[key] as number));
  const [lo, hi] = counts;
  return {
    side: s.name,
    usPerClientTick: round(((at(hi, 'cpuMsPerTick') - at(lo, 'cpuMsPerTick')) / (hi - lo)) * 1000, 2),
    cpuMsPerTick: { [lo]: round(at(lo, 'cpuMsPerTick'), 3), [hi]: round(at(hi, 'cpuMsPerTick'), 3) },
    messagesPerClientPerSecond: round(at(hi, 'messagesPerClientPerSecond'), 1),
    writesPerClientPerTick: ws[0].writesPerClientPerTick === null ? null : round(at(hi, 'writesPerClientPerTick'), 2),
    ticksPerSecondAtHigh: round(at(hi, 'ticksPerSecond'), 1),
  };
});
console.log(JSON.stringify({ clients: counts, rounds, windowMs, loadAtStart: round(load0, 1), loadAtEnd: round(loadavg()[0], 1), summary }, null, 2));
