// Start-up: process start to listening (spawn `taos-physics serve --port 0`, time until it prints its URL) for the
// default scenario and the heaviest-to-build one, with the compile cache the CLI keeps warm (every start after the
// first) and empty (the first start after an install), and each registered scenario's build time (Jolt loaded).
import '../../server/physics-node.ts';
import { mkdtempSync, rmSync } from 'node:fs';
import { tmpdir } from 'node:os';
import { join } from 'node:path';
import { fileURLToPath } from 'node:url';
import { DEFAULT_SCENARIO, listScenarios } from '../../scenarios/index.ts';
import { Simulation } from '../../shared/sim/simulation.ts';
import { CLI_PATH, runToEnd, startNode, stopChild, waitForLine } from '../lib/child.ts';
import type { ChartBar, FigureImpl, FigureOutput, ReportRow } from '../lib/figure.ts';
import { median, round } from '../lib/stats.ts';

const GOAL_MS = 1000;
const URL_LINE = /serving .* at (http:\/\/\S+)/;
const PROBE = fileURLToPath(new URL('../procs/startup-probe.ts', import.meta.url));

/** Spawns `serve --port 0 --scenario NAME` with its compile cache in `cacheDir`; ms from spawn to the line with its URL. */
async function serveOnce(scenario: string, cacheDir: string): Promise<number> {
  const t0 = performance.now();
  const child = startNode(CLI_PATH, ['serve', '--port', '0', '--scenario', scenario], { env: { NODE_COMPILE_CACHE: cacheDir } });
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
  const colds = opts.quick ? 1 : 3;
  const coldMs: number[] = [];
  opts.log(`serve: ${colds} first starts (empty compile cache), then ${spawns} spawns each of ${serveScenarios.join(', ')}`);
  for (let i = 0; i < colds; i++) {
    const empty = mkdtempSync(join(tmpdir(), 'taos-startup-cold-'));
    try {
      coldMs.push(await serveOnce(DEFAULT_SCENARIO, empty));
    } finally {
      rmSync(empty, { recursive: true, force: true });
    }
  }
  const cacheDir = mkdtempSync(join(tmpdir(), 'taos-startup-cache-'));
  const stages: Array<{ bootMs: number; importMs: number; joltMs: number; startServerMs: number; totalMs: number }> = [];
  try {
    // One unmeasured start fills the cache, as any earlier start on the machine would have.
    await serveOnce(DEFAULT_SCENARIO, cacheDir);
    for (let i = 0; i < spawns; i++) for (const s of serveScenarios) serveMs.get(s)!.push(await serveOnce(s, cacheDir));
    // Where the time goes: a probe process starts the server like serve does and times each stage from process start.
    for (let i = 0; i < spawns; i++) {
      const out = await runToEnd(startNode(PROBE, [DEFAULT_SCENARIO], { env: { NODE_COMPILE_CACHE: cacheDir } }), 30_000, 'start-up probe');
      stages.push(JSON.parse(out.trim().split('\n').at(-1)!).probe);
    }
  } finally {
    rmSync(cacheDir, { recursive: true, force: true });
  }
  const stage = (key: keyof (typeof stages)[number]): number => median(stages.map((s) => s[key]));

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
  rows.push({ figure: 'start-up', measure: `first start after an install (empty compile cache), serve --scenario ${DEFAULT_SCENARIO} (median of ${colds})`, value: median(coldMs), unit: 'ms', digits: 0 });
  rows.push({ figure: 'start-up', measure: `of which loading the server's modules (probe, median)`, value: stage('importMs'), unit: 'ms', digits: 0 });
  rows.push({ figure: 'start-up', measure: 'of which Jolt WASM load (probe, median)', value: stage('joltMs'), unit: 'ms', digits: 0 });
  const slowest = [...buildMs.entries()].sort((a, b) => b[1] - a[1])[0];
  rows.push({ figure: 'start-up', measure: `slowest scenario build: ${slowest[0]} (Jolt loaded)`, value: slowest[1], unit: 'ms', digits: 0 });
  const bars: ChartBar[] = serveScenarios.map((s) => ({ label: `serve ${s}`, value: median(serveMs.get(s)!), series: 'ours' }));
  bars.push({ label: 'probe: Node boot', value: stage('bootMs'), series: 'raw' });
  bars.push({ label: "probe: server's modules", value: stage('importMs'), series: 'other' });
  bars.push({ label: 'probe: Jolt WASM', value: stage('joltMs'), series: 'raw' });
  bars.push({ label: 'probe: room build + listen', value: stage('startServerMs'), series: 'other' });
  for (const [name, ms] of buildMs) bars.push({ label: `build ${name}`, value: ms, series: 'other' });
  return {
    headline: { startupMs: round(defaultServe, 1), startupColdMs: round(median(coldMs), 1) },
    detail: {
      serveMs: Object.fromEntries([...serveMs].map(([k, v]) => [k, v.map((x) => round(x, 1))])),
      coldServeMs: coldMs.map((x) => round(x, 1)),
      probeStagesMs: { bootMs: round(stage('bootMs'), 1), importMs: round(stage('importMs'), 1), joltMs: round(stage('joltMs'), 1), startServerMs: round(stage('startServerMs'), 1), totalMs: round(stage('totalMs'), 1) },
      joltLoadMs: round(joltLoadMs, 1),
      scenarioBuildMs: Object.fromEntries([...buildMs].map(([k, v]) => [k, round(v, 1)])),
      goalMs: GOAL_MS,
    },
    rows,
    charts: [{ title: 'Start-up (ms)', unit: 'ms', bars, goal: GOAL_MS }],
    notes: [
      `Serve: \`node bin/taos-physics.js serve --port 0 --scenario NAME\` spawned ${spawns}× per scenario, timed from spawn to the stdout line with its URL (Node start, module loading, Jolt load, the default room's build, listening); headline: ${DEFAULT_SCENARIO}, the default. The CLI keeps V8's compiled code of its modules in a compile cache (NODE_COMPILE_CACHE; here a folder of the figure's own, filled by one unmeasured start first): every start after the first on a machine finds it warm. The first start after an install (${colds}×, each with an empty folder) is reported on its own row (startupColdMs).`,
      `Stages (procs/startup-probe.ts, ${spawns} fresh processes, medians, from process start): Node boot, importing the server's TypeScript modules (type stripping + compile), Jolt's WASM, startServer (the default room's build and listening).`,
      `Builds: Simulation.create of every registered scenario in one process after Jolt is loaded (median of ${builds}), seed 1, default parameters.`,
    ],
  };
}

/** The start-up figure. */
export const figure: FigureImpl = { run };
