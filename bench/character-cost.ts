// Character cost: CPU time (this thread's, process.threadCpuUsage) of every present player's character update
// (CharacterController.move, i.e. Jolt's ExtendedUpdate plus our glue) per character per tick, and of the whole tick,
// with N scripted bots in a scene. With --against DIR (a checkout of another commit, e.g. `git archive main shared
// server | tar -x -C /tmp/base` plus a node_modules link), DIR's Simulation runs the same scene and bot records in the
// same process in alternating batches, each side on its own Jolt module, so both see the same machine load.
// The scene's player cap is lifted here: the figure is what N characters cost, not whether the room admits them.
// Run: node_modules/.bin/node bench/character-cost.ts [--scene crowd-arena|shape-rain] [--players 64,256]
//      [--warmup 180] [--ticks 300] [--batch 30] [--fire] [--against DIR]
import { join, resolve } from 'node:path';
import { pathToFileURL } from 'node:url';
import { getScenario } from '../scenarios/index.ts';
import type { ScenarioDefinition } from '../shared/sim/scenario.ts';
import type { TickInputRecord } from '../shared/sim/types.ts';

interface SimLike {
  step(record: TickInputRecord): unknown;
  playerIds(): number[];
  destroy(): void;
}

interface Side {
  label: string;
  sim: SimLike;
  records: { next(): TickInputRecord };
  /** CPU µs spent in character updates / in whole ticks, and the updates counted, over measured ticks. */
  moveUs: number;
  tickUs: number;
  updates: number;
  ticks: number;
  probe: Probe;
}

/** Times each tick's character-update loop as one span: its first update starts it, its `expected`-th ends it. */
interface Probe {
  measuring: boolean;
  expected: number;
  inTick: number;
  startUs: number;
  moveUs: number;
  updates: number;
}

interface Checkout {
  label: string;
  create(def: ScenarioDefinition, params: Record<string, number>): Promise<SimLike>;
  bots(n: number): { next(): TickInputRecord };
  /** Wraps CharacterController.prototype.move of this checkout so each call's CPU time goes to `probe`. */
  instrument(probe: () => Side['probe'] | null): void;
}

function flag(name: string): string | undefined {
  const i = process.argv.indexOf(`--${name}`);
  return i >= 0 ? process.argv[i + 1] : undefined;
}

const cpuUs = (): number => {
  const u = process.threadCpuUsage();
  return u.user + u.system;
};

async function loadCheckout(dir: string, label: string): Promise<Checkout> {
  const url = (p: string): string => pathToFileURL(join(dir, p)).href;
  await import(url('server/physics-node.ts'));
  const { Simulation } = (await import(url('shared/sim/simulation.ts'))) as typeof import('../shared/sim/simulation.ts');
  const { BotScript } = (await import(url('shared/sim/bots.ts'))) as typeof import('../shared/sim/bots.ts');
  const { CharacterController } = (await import(url('shared/physics/index.ts'))) as typeof import('../shared/physics/index.ts');
  return {
    label,
    create: (def, params) => Simulation.create({ scenario: def, params, seed: 1, worldOptions: { isolatedModule: true } }),
    bots: (n) => new BotScript({ seed: 1, bots: n, joinTicks: Array.from({ length: n }, () => 0), fire: firing }),
    instrument(probe) {
      const move = CharacterController.prototype.move;
      CharacterController.prototype.move = function (this: InstanceType<typeof CharacterController>, dtSeconds: number): void {
        const p = probe();
        if (!p?.measuring) return move.call(this, dtSeconds);
        if (p.inTick === 0) p.startUs = cpuUs();
        move.call(this, dtSeconds);
        if (++p.inTick === p.expected) {
          p.moveUs += cpuUs() - p.startUs;
          p.updates += p.inTick;
          p.inTick = 0;
        }
      };
    },
  };
}

const sceneName = flag('scene') ?? 'crowd-arena';
const counts = (flag('players') ?? '64,256').split(',').map(Number);
const warmupTicks = Number(flag('warmup') ?? 180);
const measuredTicks = Number(flag('ticks') ?? 300);
const batchTicks = Number(flag('batch') ?? 30);
const againstDir = flag('against');
/** Bots shoot only with --fire: the clients-per-core swarm does not. */
const firing = process.argv.includes('--fire');

const here = resolve(import.meta.dirname, '..');
let current: Side | null = null;
const checkouts = [await loadCheckout(here, 'this checkout')];
if (againstDir) checkouts.push(await loadCheckout(resolve(againstDir), resolve(againstDir)));
for (const c of checkouts) c.instrument(() => current?.probe ?? null);

// A CPU clock read costs something itself: measure it, and subtract one per timed loop.
let clockCost = 0;
{
  const n = 20000;
  const t0 = cpuUs();
  for (let i = 0; i < n; i++) cpuUs();
  clockCost = (cpuUs() - t0) / n;
}

const base = getScenario(sceneName);
const uncapped: ScenarioDefinition = { ...base, players: { ...base.players, maxPlayers: 4096 } };
console.log(`character cost: ${sceneName}, warmup ${warmupTicks} ticks, ${measuredTicks} measured ticks in batches of ${batchTicks}, load ${(await import('node:os')).loadavg().map((l) => l.toFixed(2)).join(' ')}`);
for (const n of counts) {
  const sides: Side[] = [];
  for (const c of checkouts) {
    const side: Side = { label: c.label, sim: await c.create(uncapped, {}), records: c.bots(n), moveUs: 0, tickUs: 0, updates: 0, ticks: 0, probe: { measuring: false, expected: 0, inTick: 0, startUs: 0, moveUs: 0, updates: 0 } };
    current = side;
    for (let t = 0; t < warmupTicks; t++) side.sim.step(side.records.next());
    sides.push(side);
  }
  for (let done = 0; done < measuredTicks; done += batchTicks) {
    const order = (done / batchTicks) % 2 === 0 ? sides : [...sides].reverse();
    for (const side of order) {
      current = side;
      side.probe.measuring = true;
      side.probe.expected = side.sim.playerIds().length; // every bot joined at tick 0 and stays
      const t0 = cpuUs();
      for (let t = 0; t < batchTicks; t++) side.sim.step(side.records.next());
      side.tickUs += cpuUs() - t0;
      side.probe.measuring = false;
      side.ticks += batchTicks;
    }
  }
  for (const side of sides) {
    const updates = side.probe.updates;
    const moveUs = side.probe.moveUs - side.ticks * clockCost;
    const present = side.sim.playerIds().length;
    console.log(
      `${n} players (${present} present) [${side.label}]: ${(moveUs / updates).toFixed(1)} µs CPU per character update, ` +
        `${(moveUs / side.ticks / 1000).toFixed(2)} ms of character updates and ${(side.tickUs / side.ticks / 1000).toFixed(2)} ms CPU per whole tick`,
    );
    side.sim.destroy();
  }
  if (sides.length === 2) {
    const ratio = (sides[0].probe.moveUs / sides[0].probe.updates) / (sides[1].probe.moveUs / sides[1].probe.updates);
    console.log(`${n} players: this checkout / ${sides[1].label} per character update ${ratio.toFixed(3)}×`);
  }
}
