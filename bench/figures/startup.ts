// Start-up: process start to listening (spawn `taos-physics serve --port 0`, time until it prints its URL) for the
// default scenario and the heaviest-to-build one, and each registered scenario's build time (Jolt already loaded).
import '../../server/physics-node.ts';
import { mkdtemp, rm } from 'node:fs/promises';
import { tmpdir } from 'node:os';
import { join } from 'node:path';
import { DEFAULT_SCENARIO, listScenarios } from '../../scenarios/index.ts';
import { Simulation } from '../../shared/sim/simulation.ts';
import { CLI_PATH, startNode, stopChild, waitForLine } from '../lib/child.ts';
import type { ChartBar, FigureImpl, FigureOutput, ReportRow } from '../lib/figure.ts';
import { median, round } from '../lib/stats.ts';

const GOAL_MS = 1000;
const URL_LINE = /serving .* at (http:\/\/\S+)/;

/** Spawns `serve --port 0 --scenario NAME` and returns ms from spawn to the line with its URL. */
async function serveOnce(scenario: string, env?: Record<string, string>): Promise<number> {
  const t0 = performance.now();
  const child = startNode(CLI_PATH, ['serve', '--port', '0', '--scenario', scenario], { env });
  try {
    const { atMs } = await waitForLine(child, URL_LINE, 30_000);
    return atMs - t0;
  } finally {
    await stopChild(child);
  }
}

async function run(opts: { quick: boolean; log(m: string): void }): Promise<FigureOutput> {
  const spawns = opts.quick ? 3 : 7;
  const builds = opts.quick ? 1 : 3;
  const serveScenarios = [DEFAULT_SCENARIO, 'cubes-901'];
  const serveMs = new Map<string, number[]>(serveScenarios.map((s) => [s, []]));
  opts.log(`serve: ${spawns} spawns each of ${serveScenarios.join(', ')}`);
  // Diagnostic: the same start with Node's on-disk compile cache warm (NODE_COMPILE_CACHE; the first spawn fills it),
  // which shows how much of the start is compiling the TypeScript modules.
  const cacheDir = await mkdtemp(join(tmpdir(), 'taos-bench-ncc-'));
  const cachedMs: number[] = [];
  try {
    for (let i = 0; i < spawns; i++) {
      for (const s of serveScenarios) serveMs.get(s)!.push(await serveOnce(s));
      const ms = await serveOnce(DEFAULT_SCENARIO, { NODE_COMPILE_CACHE: cacheDir });
      if (i > 0) cachedMs.push(ms);
    }
  } finally {
    await rm(cacheDir, { recursive: true, force: true });
  }

  // The first world in a process also loads Jolt's WASM: timed apart.
  const scenarios = listScenarios();
  let joltLoadMs = 0;
  {
    const t0 = performance.now();
    const first = await Simulation.create({ scenario: scenarios[0], seed: 1 });
    joltLoadMs = performance.now() - t0;
    first.destroy();
  }
  const buildMs = new Map<string, number>();
  opts.log(`scenario builds: ${builds} of each of ${scenarios.length}`);
  for (const def of scenarios) {
    const times: number[] = [];
    for (let i = 0; i < builds; i++) {
      const t0 = performance.now();
      const sim = await Simulation.create({ scenario: def, seed: 1 });
      times.push(performance.now() - t0);
      sim.destroy();
    }
    buildMs.set(def.name, median(times));
  }
  const defaultServe = median(serveMs.get(DEFAULT_SCENARIO)!);
  const rows: ReportRow[] = serveScenarios.map((s) => ({
    figure: 'start-up',
    measure: `process start → listening, serve --scenario ${s} (median of ${spawns})`,
    value: median(serveMs.get(s)!),
    unit: 'ms',
    digits: 0,
    goal: { op: '<=' as const, value: GOAL_MS },
  }));
  rows.push({ figure: 'start-up', measure: `same, ${DEFAULT_SCENARIO}, Node compile cache warm (diagnostic)`, value: median(cachedMs), unit: 'ms', digits: 0 });
  rows.push({ figure: 'start-up', measure: 'Jolt WASM load (first world in a process)', value: joltLoadMs, unit: 'ms', digits: 0 });
  const slowest = [...buildMs.entries()].sort((a, b) => b[1] - a[1])[0];
  rows.push({ figure: 'start-up', measure: `slowest scenario build: ${slowest[0]} (Jolt loaded)`, value: slowest[1], unit: 'ms', digits: 0 });
  const bars: ChartBar[] = serveScenarios.map((s) => ({ label: `serve ${s}`, value: median(serveMs.get(s)!), series: 'ours' }));
  bars.push({ label: `serve ${DEFAULT_SCENARIO}, compile cache warm`, value: median(cachedMs), series: 'other' });
  bars.push({ label: 'Jolt WASM load', value: joltLoadMs, series: 'raw' });
  for (const [name, ms] of buildMs) bars.push({ label: `build ${name}`, value: ms, series: 'other' });
  return {
    headline: { startupMs: round(defaultServe, 1) },
    detail: {
      serveMs: Object.fromEntries([...serveMs].map(([k, v]) => [k, v.map((x) => round(x, 1))])),
      serveWithCompileCacheMs: cachedMs.map((x) => round(x, 1)),
      joltLoadMs: round(joltLoadMs, 1),
      scenarioBuildMs: Object.fromEntries([...buildMs].map(([k, v]) => [k, round(v, 1)])),
      goalMs: GOAL_MS,
    },
    rows,
    charts: [{ title: 'Start-up (ms)', unit: 'ms', bars, goal: GOAL_MS }],
    notes: [
      `Serve: \`node bin/taos-physics.js serve --port 0 --scenario NAME\` spawned ${spawns}× per scenario, timed from spawn to the stdout line with its URL (Node start, module loading, Jolt load, the default room's build, listening); headline: ${DEFAULT_SCENARIO}, the default.`,
      'Diagnostic: the default start again with NODE_COMPILE_CACHE pointing at a warm cache (Node keeps compiled, type-stripped modules on disk); the gap to the plain start is the cost of compiling ~140 TypeScript modules on every start.',
      `Builds: Simulation.create of every registered scenario in one process after Jolt is loaded (median of ${builds}), seed 1, default parameters.`,
    ],
  };
}

/** The start-up figure. */
export const figure: FigureImpl = { run };
