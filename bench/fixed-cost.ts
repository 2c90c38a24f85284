// Fixed cost: on the 1000-body shape-rain pile, (1) a replay of a CLI recording (a hash every tick) against the floor
// of the same ticks, and (2) the simulation's own per-tick work (step, state hash, snapshot read) with 16 bots against
// the floor (characters + bare step), in CPU ms of this thread (steadier than wall time on a loaded machine). With
// --against DIR (a checkout of another commit, e.g. `git archive main | tar -x -C /tmp/base` plus a node_modules
// link), DIR's code runs in the same process in alternating passes and batches, each side on its own Jolt module.
// Run: node_modules/.bin/node bench/fixed-cost.ts [--ticks 600] [--rounds 3] [--against DIR]
import { mkdtemp, rm } from 'node:fs/promises';
import { tmpdir } from 'node:os';
import { join, resolve } from 'node:path';
import { pathToFileURL } from 'node:url';
import { CLI_PATH, REPO_ROOT, runToEnd, startNode } from './lib/child.ts';

function flag(name: string): string | undefined {
  const i = process.argv.indexOf(`--${name}`);
  return i >= 0 ? process.argv[i + 1] : undefined;
}

const ticks = Number(flag('ticks') ?? 600);
const rounds = Number(flag('rounds') ?? 3);
const againstDir = flag('against');
const BATCH_TICKS = 15;
const BOTS = 16;

/** What this bench drives of one checkout. */
interface Side {
  name: string;
  replayLog(file: string): Promise<{ status: string; ticks: number }>;
  floorStepBatch(sim: Sim, ticks: number): unknown[];
  createPile(): Promise<Sim>;
  readyTick: number;
  records(file: string): Promise<TickRecord[]>;
  bots(): { next(): TickRecord };
}
/** A tick input record (only its tick number is touched here). */
type TickRecord = { tick: number };
interface Sim {
  readonly tick: number;
  step(record: TickRecord): unknown;
  stateHash(): string;
  readBodyStates(): unknown;
  destroy(): void;
}

async function loadSide(name: string, dir: string): Promise<Side> {
  const at = async <T>(path: string): Promise<T> => (await import(pathToFileURL(join(dir, path)).href)) as T;
  const replay = await at<{ replayLog: Side['replayLog'] }>('cli/replay-session.ts');
  const raw = await at<{ floorStepBatch: Side['floorStepBatch'] }>('bench/lib/raw-step.ts');
  const scenes = await at<{ createSceneSim(s: object): Promise<Sim>; PILE_SCENE: object; PILE_READY_TICK: number }>('bench/lib/scenes.ts');
  const log = await at<{ LogReader: { open(f: string): Promise<{ entries(): AsyncIterable<{ type: string; record: TickRecord }>; close(): Promise<void> }> } }>('server/log/index.ts');
  const bots = await at<{ BotScript: new (o: object) => { next(): TickRecord } }>('shared/sim/bots.ts');
  return {
    name,
    replayLog: replay.replayLog,
    floorStepBatch: raw.floorStepBatch,
    createPile: () => scenes.createSceneSim(scenes.PILE_SCENE),
    readyTick: scenes.PILE_READY_TICK,
    async records(file) {
      const reader = await log.LogReader.open(file);
      const out: TickRecord[] = [];
      for await (const e of reader.entries()) if (e.type === 'tick') out.push(e.record);
      await reader.close();
      return out;
    },
    bots: () => new bots.BotScript({ seed: 1, bots: BOTS, joinTicks: Array.from({ length: BOTS }, () => 0) }),
  };
}

const cpuMs = (): number => {
  const u = process.threadCpuUsage();
  return (u.user + u.system) / 1000;
};
const median = (xs: number[]): number => xs.slice().sort((a, b) => a - b)[xs.length >> 1];

async function replayPass(side: Side, file: string): Promise<number> {
  const t0 = cpuMs();
  const report = await side.replayLog(file);
  const ms = cpuMs() - t0;
  if (report.status !== 'ok' || report.ticks !== ticks) throw new Error(`${side.name}: replay ${report.status} after ${report.ticks} ticks`);
  return ms;
}

/** The floor of the log's ticks, in batches from fast checkpoints (as the replay figure's floor). */
async function floorPass(side: Side, records: readonly TickRecord[]): Promise<number> {
  const sim = await side.createPile();
  try {
    let total = 0;
    for (let i = 0; i < records.length; i += BATCH_TICKS) {
      const batch = records.slice(i, i + BATCH_TICKS);
      const t0 = cpuMs();
      side.floorStepBatch(sim, batch.length);
      total += cpuMs() - t0;
      for (const r of batch) sim.step(r);
    }
    return total;
  } finally {
    sim.destroy();
  }
}

/** Per tick: the floor of BATCH_TICKS ticks, then the same ticks through step + stateHash + readBodyStates. */
function tickBatch(side: Side, sim: Sim, bots: { next(): TickRecord }): { floorMs: number; fullMs: number; hashReadMs: number } {
  const t0 = cpuMs();
  side.floorStepBatch(sim, BATCH_TICKS);
  const floorMs = (cpuMs() - t0) / BATCH_TICKS;
  let full = 0;
  let hashRead = 0;
  for (let i = 0; i < BATCH_TICKS; i++) {
    const record = { ...bots.next(), tick: sim.tick };
    const a = cpuMs();
    sim.step(record);
    const b = cpuMs();
    sim.stateHash();
    sim.readBodyStates();
    const c = cpuMs();
    full += c - a;
    hashRead += c - b;
  }
  return { floorMs, fullMs: full / BATCH_TICKS, hashReadMs: hashRead / BATCH_TICKS };
}

const sides = [await loadSide('this checkout', REPO_ROOT)];
if (againstDir) sides.push(await loadSide(resolve(againstDir), resolve(againstDir)));
const dir = await mkdtemp(join(tmpdir(), 'taos-fixed-cost-'));
try {
  const file = join(dir, 'pile.taoslog');
  await runToEnd(startNode(CLI_PATH, ['record', '--scenario', 'shape-rain', '--param', 'count=1000', '--bots', '1', '--ticks', String(ticks), '--out', file, '--json']), 300_000, 'record');
  const records = await sides[0].records(file);
  for (const side of sides) await replayPass(side, file); // loads Jolt, warms the code paths
  const replay = sides.map(() => ({ replay: [] as number[], floor: [] as number[] }));
  for (let r = 0; r < rounds; r++) {
    for (let s = 0; s < sides.length; s++) replay[s].replay.push(await replayPass(sides[s], file));
    for (let s = 0; s < sides.length; s++) replay[s].floor.push(await floorPass(sides[s], records));
  }
  const sims = await Promise.all(sides.map(async (side) => {
    const sim = await side.createPile();
    while (sim.tick < side.readyTick) sim.step({ tick: sim.tick, leaves: [], joins: [], commands: [] } as TickRecord);
    return { sim, bots: side.bots() };
  }));
  const perTick = sides.map(() => ({ floorMs: [] as number[], fullMs: [] as number[], hashReadMs: [] as number[] }));
  for (let b = 0; b < rounds * 8; b++) {
    for (let s = 0; s < sides.length; s++) {
      const t = tickBatch(sides[s], sims[s].sim, sims[s].bots);
      perTick[s].floorMs.push(t.floorMs);
      perTick[s].fullMs.push(t.fullMs);
      perTick[s].hashReadMs.push(t.hashReadMs);
    }
  }
  for (const { sim } of sims) sim.destroy();
  for (let s = 0; s < sides.length; s++) {
    const r = replay[s];
    const t = perTick[s];
    const ratios = r.replay.map((v, i) => (v / r.floor[i]).toFixed(3));
    console.log(`${sides[s].name}`);
    console.log(`  replay/floor, ${ticks} ticks of shape-rain 1000 with 1 bot: ${(median(r.replay) / median(r.floor)).toFixed(3)} (medians ${median(r.replay).toFixed(0)}/${median(r.floor).toFixed(0)} CPU ms; per pass pair ${ratios.join(' ')}, median ${median(ratios.map(Number)).toFixed(3)})`);
    const over = t.fullMs.map((v, i) => v - t.floorMs[i]); // each batch against its own floor: load drift cancels
    console.log(`  per tick, ${BOTS} bots from tick ${sides[s].readyTick}: floor ${median(t.floorMs).toFixed(3)}, step+hash+read ${median(t.fullMs).toFixed(3)} (hash+read ${median(t.hashReadMs).toFixed(3)}), over the floor ${median(over).toFixed(3)} CPU ms (median of ${over.length} batches)`);
  }
} finally {
  await rm(dir, { recursive: true, force: true });
}
