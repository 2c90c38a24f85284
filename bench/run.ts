// `npm run bench`: runs every figure, each in its own Node process, prints one table and writes
// bench/results/latest.{json,md} plus one SVG chart per figure. Flags: --quick, --json, --peers, --only NAME, --out DIR.
import { spawn } from 'node:child_process';
import { mkdir, mkdtemp, readdir, readFile, rm, writeFile } from 'node:fs/promises';
import { cpus, loadavg, platform, release, tmpdir, totalmem } from 'node:os';
import { join } from 'node:path';
import { fileURLToPath } from 'node:url';
import { FIGURE_NAMES, FIGURES, HEADLINE_KEYS } from './figures/index.ts';
import { benchUsage, parseBenchArgs } from './lib/args.ts';
import type { FigureOutput, FigureSpec } from './lib/figure.ts';
import { describeLoad, renderMarkdownPage, renderTable, type FigureStatus, type MachineInfo, type PageSection } from './lib/report.ts';
import { allRows, assembleResults, type FigureRun } from './lib/results.ts';
import { renderChartSvg } from './lib/svg.ts';

const benchDir = fileURLToPath(new URL('.', import.meta.url));

/** /proc/loadavg, or the 1/5/15-minute load averages where the file is missing. */
async function readLoad(): Promise<string> {
  try {
    return (await readFile('/proc/loadavg', 'utf8')).trim();
  } catch {
    return loadavg()
      .map((v) => v.toFixed(2))
      .join(' ');
  }
}

async function machineInfo(): Promise<MachineInfo> {
  const cpu = cpus();
  const loadAverage1m = Math.round(loadavg()[0] * 100) / 100;
  return {
    cpuModel: cpu[0]?.model.trim() ?? 'unknown',
    cores: cpu.length,
    nodeVersion: process.version,
    platform: `${platform()} ${release()}`,
    totalMemoryMiB: Math.round(totalmem() / 1048576),
    loadAverage1m,
    loadAtStart: await readLoad(),
    loadAtEnd: null,
    loadNote: describeLoad(cpu.length, loadAverage1m, null),
  };
}

/** Runs one figure in a child process with a time limit; its progress goes to our stderr. */
async function runFigure(spec: FigureSpec, quick: boolean, scratch: string): Promise<FigureRun> {
  const resultFile = join(scratch, `${spec.name}.json`);
  const args = [join(benchDir, 'lib', 'figure-process.ts'), spec.name, resultFile, ...(quick ? ['--quick'] : [])];
  const started = performance.now();
  const limitMs = spec.timeLimitMs(quick);
  // Its own process group, so a figure that overruns is stopped together with the servers and bots it spawned.
  const child = spawn(process.execPath, args, { stdio: ['ignore', 'inherit', 'inherit'], detached: true });
  let timedOut = false;
  const killGroup = (signal: NodeJS.Signals): void => {
    try {
      if (child.pid !== undefined) process.kill(-child.pid, signal);
    } catch {
      // already gone
    }
  };
  const timer = setTimeout(() => {
    timedOut = true;
    killGroup('SIGTERM');
    setTimeout(() => killGroup('SIGKILL'), 5000).unref();
  }, limitMs);
  const code = await new Promise<number | null>((resolve) => child.on('exit', (c) => resolve(c)));
  clearTimeout(timer);
  killGroup('SIGKILL'); // anything the figure left running
  const seconds = Math.round((performance.now() - started) / 100) / 10;
  let parsed: { ok: boolean; output?: FigureOutput; error?: string } | null = null;
  try {
    parsed = JSON.parse(await readFile(resultFile, 'utf8')) as { ok: boolean; output?: FigureOutput; error?: string };
  } catch {
    parsed = null;
  }
  let status: FigureStatus;
  if (timedOut) status = { status: 'failed', seconds, error: `ran past its ${Math.round(limitMs / 1000)} s limit` };
  else if (parsed?.ok && parsed.output) status = { status: 'ok', seconds };
  else status = { status: 'failed', seconds, error: parsed?.error ?? `the figure's process exited with code ${code} without a result` };
  return { spec, status, output: status.status === 'ok' ? parsed!.output! : null };
}

async function writeResults(outDir: string, runs: readonly FigureRun[], results: Record<string, unknown>, page: { quick: boolean; startedAt: string; durationSeconds: number; machine: MachineInfo }): Promise<void> {
  await mkdir(outDir, { recursive: true });
  const sections: PageSection[] = [];
  for (const run of runs) {
    const charts = (run.output?.charts ?? []).map((_, i) => `${run.spec.name}${i === 0 ? '' : `-${i + 1}`}.svg`);
    for (let i = 0; i < charts.length; i++) await writeFile(join(outDir, charts[i]), renderChartSvg(run.output!.charts[i]));
    sections.push({ title: run.spec.title, charts, notes: run.output?.notes ?? [], status: run.status });
  }
  // Charts of figures that did not run this time would describe another run: remove them.
  const written = new Set(sections.flatMap((s) => s.charts));
  for (const name of await readdir(outDir)) {
    const figure = FIGURES.find((f) => name === `${f.name}.svg` || new RegExp(`^${f.name}-\\d+\\.svg$`).test(name));
    if (figure && !written.has(name)) await rm(join(outDir, name));
  }
  await writeFile(join(outDir, 'latest.json'), `${JSON.stringify(results, null, 2)}\n`);
  await writeFile(join(outDir, 'latest.md'), renderMarkdownPage({ ...page, rows: allRows(runs), sections }));
}

async function main(): Promise<number> {
  let args;
  try {
    args = parseBenchArgs(process.argv.slice(2), FIGURE_NAMES);
  } catch (error) {
    process.stderr.write(`bench: ${(error as Error).message}\n\n${benchUsage(FIGURE_NAMES)}`);
    return 2;
  }
  if (args.help) {
    process.stdout.write(benchUsage(FIGURE_NAMES));
    return 0;
  }
  const selected = FIGURES.filter((f) => (args.only.length > 0 ? args.only.includes(f.name) : !f.peersOnly || args.peers));
  const machine = await machineInfo();
  const startedAt = new Date().toISOString();
  const t0 = performance.now();
  process.stderr.write(`bench: ${args.quick ? 'quick' : 'full'} run of ${selected.map((f) => f.name).join(', ')} on ${machine.cores} × ${machine.cpuModel} (load ${machine.loadAverage1m})\n`);
  const scratch = await mkdtemp(join(tmpdir(), 'taos-bench-'));
  const runs: FigureRun[] = [];
  try {
    for (const spec of selected) {
      process.stderr.write(`bench: ${spec.name}…\n`);
      const run = await runFigure(spec, args.quick, scratch);
      process.stderr.write(`bench: ${spec.name} ${run.status.status} in ${run.status.seconds} s${run.status.error ? ` (${run.status.error})` : ''}\n`);
      runs.push(run);
    }
  } finally {
    await rm(scratch, { recursive: true, force: true });
  }
  const durationSeconds = (performance.now() - t0) / 1000;
  machine.loadAtEnd = await readLoad();
  machine.loadNote = describeLoad(machine.cores, machine.loadAverage1m, Math.round(loadavg()[0] * 100) / 100);
  const results = assembleResults({ headlineKeys: HEADLINE_KEYS, runs, machine, quick: args.quick, startedAt, durationSeconds });
  const table = renderTable(allRows(runs));
  if (args.json) {
    process.stderr.write(`\n${table}`);
    process.stdout.write(`${JSON.stringify(results, null, 2)}\n`);
  } else process.stdout.write(`\n${table}`);
  const outDir = args.outDir ?? (args.only.length === 0 ? join(benchDir, 'results') : null);
  if (outDir !== null) {
    await writeResults(outDir, runs, results, { quick: args.quick, startedAt, durationSeconds, machine });
    process.stderr.write(`bench: results written to ${outDir}\n`);
  }
  return runs.some((r) => r.status.status === 'failed') ? 1 : 0;
}

process.exitCode = await main();
