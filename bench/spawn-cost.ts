// Spawn cost: the per-tick body churn of a bullet-heavy room (spawn bullets, remove the oldest, read every body's
// state) beside 1,000 boxes, in µs per tick. With --against DIR (a checkout of another commit, e.g.
// `git archive main shared server | tar -x -C /tmp/base` plus a node_modules link), DIR's PhysicsWorld runs in the
// same process in alternating batches, each side on its own Jolt module.
// Run: node_modules/.bin/node bench/spawn-cost.ts [--rounds 15] [--spawns-per-tick 4] [--against DIR]
import { join, resolve } from 'node:path';
import { pathToFileURL } from 'node:url';
import '../server/physics-node.ts';
import { PhysicsWorld } from '../shared/physics/index.ts';

/** The slice of PhysicsWorld this bench drives (so another checkout's world fits it too). */
interface World {
  addBox(half: { x: number; y: number; z: number }, pos: { x: number; y: number; z: number }, rot: null, opts: { motion: 'static' | 'dynamic' }): { id: number };
  addSphere(radius: number, pos: { x: number; y: number; z: number }): { id: number };
  removeBody(id: number): void;
  readBodyStates(): { count: number };
}

function flag(name: string): string | undefined {
  const i = process.argv.indexOf(`--${name}`);
  return i >= 0 ? process.argv[i + 1] : undefined;
}

const rounds = Number(flag('rounds') ?? 15);
const spawnsPerTick = Number(flag('spawns-per-tick') ?? 4);
const ticksPerBatch = 250;
const liveBullets = 200;
const againstDir = flag('against');

async function makeWorld(create: () => Promise<World>): Promise<{ world: World; live: number[] }> {
  const world = await create();
  world.addBox({ x: 50, y: 1, z: 50 }, { x: 0, y: -1, z: 0 }, null, { motion: 'static' });
  for (let i = 0; i < 1000; i++) world.addBox({ x: 0.3, y: 0.3, z: 0.3 }, { x: (i % 20) * 0.7 - 7, y: 1 + Math.floor(i / 20) * 0.7, z: 0 }, null, { motion: 'dynamic' });
  world.readBodyStates();
  return { world, live: [] };
}

/** ms for one batch of ticks: spawn, remove the oldest past `liveBullets`, read every body. */
function batch(side: { world: World; live: number[] }): number {
  const { world, live } = side;
  const t0 = performance.now();
  for (let t = 0; t < ticksPerBatch; t++) {
    for (let s = 0; s < spawnsPerTick; s++) live.push(world.addSphere(0.05, { x: ((t * 7 + s) % 30) - 15, y: 5, z: 3 }).id);
    while (live.length > liveBullets) world.removeBody(live.shift()!);
    world.readBodyStates();
  }
  return performance.now() - t0;
}

const median = (xs: number[]): number => xs.slice().sort((a, b) => a - b)[xs.length >> 1];

const sides: Array<[string, { world: World; live: number[] }]> = [['this checkout', await makeWorld(() => PhysicsWorld.create({ isolatedModule: true }) as Promise<World>)]];
if (againstDir) {
  const dir = resolve(againstDir);
  await import(pathToFileURL(join(dir, 'server/physics-node.ts')).href);
  const other = (await import(pathToFileURL(join(dir, 'shared/physics/index.ts')).href)) as { PhysicsWorld: { create(o: object): Promise<World> } };
  sides.push([dir, await makeWorld(() => other.PhysicsWorld.create({ isolatedModule: true }))]);
}
const times = sides.map(() => [] as number[]);
for (let r = 0; r < rounds; r++) {
  const order = r % 2 === 0 ? sides.map((_, i) => i) : sides.map((_, i) => sides.length - 1 - i);
  for (const i of order) times[i].push(batch(sides[i][1]));
}
const bodies = sides[0][1].world.readBodyStates().count;
const usPerTick = times.map((t) => (median(t) * 1000) / ticksPerBatch);
for (let i = 0; i < sides.length; i++) {
  const vs = i === 0 ? '' : ` (this checkout ${usPerTick[0] - usPerTick[i] >= 0 ? '+' : ''}${(usPerTick[0] - usPerTick[i]).toFixed(1)} µs, ×${(usPerTick[0] / usPerTick[i]).toFixed(2)})`;
  console.log(`${sides[i][0]}: ${usPerTick[i].toFixed(1)} µs per tick${vs}`);
}
console.log(`each tick: ${spawnsPerTick} spawns, ${spawnsPerTick} removals, a read of ${bodies} bodies; median of ${rounds} batches of ${ticksPerBatch} ticks`);
