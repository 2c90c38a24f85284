// Per-client cost of the server's tick, in process (issue 14 item 4): the tick-overhead rig (bench/lib/server-rig.ts:
// the real GameServer, room, sessions and encoders; clients that send what the client library sends) on stock
// shape-rain 300 with 30 Hz snapshots, at two client counts. The server's share of each tick (arrived messages +
// Room.tickOnce) is timed with process.cpuUsage (CPU time: another process taking the core does not count); the cost
// per client per tick is the slope between the two counts, for the whole tick and for its network part (taking client
// messages, delivering events and snapshots: CPU time of each call). Sockets are not in it (per-client-writes.ts).
// With --against DIR (a checkout of another commit, e.g. `git archive main | tar -x -C DIR`, node_modules linked), DIR's
// rigs run beside these, a tick of each in turn, so before/after share the machine's load tick by tick.
// --scene crowd-arena measures the crowd scene (one spawn point per player) instead of shape-rain 300.
// Run: node_modules/.bin/node bench/per-client-cost.ts [--clients 16,96] [--rounds 3] [--ticks 300] [--scene crowd-arena] [--against DIR]
import { loadavg } from 'node:os';
import { join, resolve } from 'node:path';
import { pathToFileURL } from 'node:url';
import type * as Rig from './lib/server-rig.ts';
import { median, round } from './lib/stats.ts';

const argv = process.argv.slice(2);
const flag = (name: string): string | undefined => {
  const i = argv.indexOf(`--${name}`);
  return i >= 0 ? argv[i + 1] : undefined;
};
const counts = (flag('clients') ?? '16,96').split(',').map(Number);
const rounds = Number(flag('rounds') ?? 3);
const ticks = Number(flag('ticks') ?? 300);
const warmTicks = Number(flag('warm') ?? 240);
const againstDir = flag('against');
const SCENES = { 'shape-rain': { scenario: 'shape-rain', params: { count: 300 }, label: 'shape-rain 300' }, 'crowd-arena': { scenario: 'crowd-arena', params: {}, label: 'crowd-arena' } } as const;
const sceneName = flag('scene') ?? 'shape-rain';
if (!(sceneName in SCENES)) throw new Error(`--scene takes ${Object.keys(SCENES).join(' or ')}, got ${sceneName}`);
const scene = SCENES[sceneName as keyof typeof SCENES];
if (counts.length !== 2 || !counts.every((n) => Number.isInteger(n) && n > 0) || counts[0] >= counts[1]) throw new Error('--clients takes two counts, low,high');

interface Side {
  name: string;
  rig: typeof Rig;
  /** Client messages the side's sessions have taken so far. */
  received: () => number;
  /** CPU µs spent so far taking client messages and handing members their events and snapshots. */
  networkCpuUs: () => number;
}

/** One rig's measured ticks: CPU ms per server tick, its network part, client messages per client per tick. */
interface Run {
  clients: number;
  cpuMsPerTick: number;
  networkMsPerTick: number;
  messagesPerClientPerTick: number;
}

type StartedRig = Awaited<ReturnType<typeof Rig.startServerRig>>;

/**
 * Every side at both counts at once, a tick of each in turn (the order rotating), so a burst of load on this shared
 * machine hits all of them alike: per rig, the CPU time of its serverTick() and of the network calls inside it.
 */
async function runAll(sides: readonly Side[]): Promise<Map<string, Run[]>> {
  const rigs: Array<{ side: Side; clients: number; rig: StartedRig; cpuUs: number; networkUs: number; received: number }> = [];
  try {
    for (const side of sides) {
      for (const clients of counts) {
        const rig = await side.rig.startServerRig({ scenario: scene.scenario, params: scene.params, startBytes: null, clients, snapshotRateHz: 30, oneWayTicks: 2, hashEveryTicks: 60 });
        rigs.push({ side, clients, rig, cpuUs: 0, networkUs: 0, received: 0 });
      }
    }
    for (let t = 0; t < warmTicks + ticks; t++) {
      for (let k = 0; k < rigs.length; k++) {
        const r = rigs[(k + t) % rigs.length];
        const n0 = r.side.networkCpuUs();
        const m0 = r.side.received();
        const c0 = process.cpuUsage();
        r.rig.serverTick();
        const c = process.cpuUsage(c0);
        if (t >= warmTicks) {
          r.cpuUs += c.user + c.system;
          r.networkUs += r.side.networkCpuUs() - n0;
          r.received += r.side.received() - m0;
        }
        await r.rig.clientTick();
      }
    }
  } finally {
    for (const r of rigs) await r.rig.close();
  }
  const out = new Map<string, Run[]>(sides.map((s) => [s.name, []]));
  for (const r of rigs) out.get(r.side.name)!.push({ clients: r.clients, cpuMsPerTick: r.cpuUs / 1000 / ticks, networkMsPerTick: r.networkUs / 1000 / ticks, messagesPerClientPerTick: r.received / r.clients / ticks });
  return out;
}

async function side(name: string, root: string): Promise<Side> {
  const rig = (await import(pathToFileURL(join(root, 'bench/lib/server-rig.ts')).href)) as typeof Rig;
  type Proto = { prototype: Record<string, unknown> };
  const { ClientSession } = (await import(pathToFileURL(join(root, 'server/client-session.ts')).href)) as { ClientSession: Proto };
  const { DeliveringMember } = (await import(pathToFileURL(join(root, 'server/member-delivery.ts')).href)) as { DeliveringMember: Proto };
  let received = 0;
  let networkUs = 0;
  // Every frame a session takes passes its onMessage (a private method of both versions), every delivery a member's
  // deliverFrame or deliverEvents: count and time them (the same wrapper cost on both sides).
  const timed = (proto: Record<string, unknown>, name: string, count: boolean): void => {
    const original = proto[name] as (...args: unknown[]) => void;
    proto[name] = function timedCall(this: unknown, ...args: unknown[]): void {
      if (count) received++;
      const c0 = process.cpuUsage();
      try {
        original.apply(this, args);
      } finally {
        const c = process.cpuUsage(c0);
        networkUs += c.user + c.system;
      }
    };
  };
  timed(ClientSession.prototype, 'onMessage', true);
  timed(DeliveringMember.prototype, 'deliverFrame', false);
  timed(DeliveringMember.prototype, 'deliverEvents', false);
  return { name, rig, received: () => received, networkCpuUs: () => networkUs };
}

const sides = [await side('now', resolve('.'))];
if (againstDir) sides.push(await side(againstDir, resolve(againstDir)));
const results = new Map<string, Run[]>(sides.map((s) => [s.name, []]));
const load0 = loadavg()[0];
for (let r = 0; r < rounds; r++) {
  for (const [name, runs] of await runAll(sides)) {
    results.get(name)!.push(...runs);
    for (const x of runs) console.error(`round ${r + 1} ${name} ${x.clients} clients: ${x.cpuMsPerTick.toFixed(3)} ms CPU/tick, network part ${x.networkMsPerTick.toFixed(3)} ms CPU/tick, ${x.messagesPerClientPerTick.toFixed(2)} msg/client/tick`);
  }
}
const [lo, hi] = counts;
const summary = sides.map((s) => {
  const xs = results.get(s.name)!;
  const at = (n: number, key: 'cpuMsPerTick' | 'networkMsPerTick' | 'messagesPerClientPerTick'): number => median(xs.filter((x) => x.clients === n).map((x) => x[key]));
  const slopeUs = (key: 'cpuMsPerTick' | 'networkMsPerTick'): number => round(((at(hi, key) - at(lo, key)) / (hi - lo)) * 1000, 2);
  return {
    side: s.name,
    usPerClientTick: slopeUs('cpuMsPerTick'),
    networkUsPerClientTick: slopeUs('networkMsPerTick'),
    cpuMsPerTick: { [lo]: round(at(lo, 'cpuMsPerTick'), 3), [hi]: round(at(hi, 'cpuMsPerTick'), 3) },
    messagesPerClientPerTick: round(at(hi, 'messagesPerClientPerTick'), 3),
  };
});
console.log(JSON.stringify({ scene: scene.label, snapshotRateHz: 30, clients: counts, rounds, ticks, loadAtStart: round(load0, 1), loadAtEnd: round(loadavg()[0], 1), summary }, null, 2));
