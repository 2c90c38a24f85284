// `verify FILE [--runs N] [--workers] [--json]`: replays a log in N separate processes (or worker threads) at once
// and compares their per-tick hash sequences with each other and with the log; exit 1 on any difference.
import { spawn } from 'node:child_process';
import { availableParallelism } from 'node:os';
import { join, resolve } from 'node:path';
import { Worker } from 'node:worker_threads';
import { LogReader } from '../server/log/log-reader.ts';
import { PACKAGE_ROOT, siblingModuleUrl } from '../server/package-root.ts';
import type { ParsedArgs } from './args.ts';
import { ExitCode, UsageError, type CliIo, type CommandSpec } from './command.ts';
import { describeFailure, SCENARIO_MODULE_FLAGS, type ReplayVerdict } from './replay-command.ts';
import { scenarioFromArg } from './scenario-setup.ts';
import type { ReplayReport } from './replay-session.ts';

const BIN = join(PACKAGE_ROOT, 'bin', 'taos-physics.js');

/** One replay's per-tick hashes and verdict, as verify sees it. */
interface RunResult {
  status: ReplayReport['status'];
  hashes: string[];
  msPerTick: number;
  report: ReplayVerdict;
}

const STATUSES: ReadonlySet<string> = new Set<ReplayReport['status']>(['ok', 'diverged', 'corrupt']);

/** The verdict and hashes in what `replay --json --hashes` printed; null when it is not that. */
function parseReplayJson(parsed: unknown): RunResult | null {
  if (parsed === null || typeof parsed !== 'object' || Array.isArray(parsed)) return null;
  const p = parsed as Record<string, unknown>;
  if (typeof p.status !== 'string' || !STATUSES.has(p.status) || !Array.isArray(p.hashes) || typeof p.ticks !== 'number' || typeof p.hashesChecked !== 'number') return null;
  const report: ReplayVerdict = { status: p.status as ReplayReport['status'], ticks: p.ticks, hashesChecked: p.hashesChecked };
  if (p.divergence) report.divergence = p.divergence as ReplayReport['divergence'];
  if (p.corruption) report.corruption = p.corruption as ReplayReport['corruption'];
  if (typeof p.warning === 'string') report.joltVersionNote = p.warning;
  return { status: report.status, hashes: p.hashes as string[], msPerTick: Number(p.msPerTick), report };
}

/** Which scenario module a replay loads (a log of a game's own scenario) and whether it may differ. */
interface ScenarioChoice {
  scenarioPath?: string;
  force: boolean;
}

/** Replays in a child process running this same CLI (`replay FILE --json --hashes`). */
function replayInProcess(file: string, choice: ScenarioChoice): Promise<RunResult> {
  const extra = [...(choice.scenarioPath !== undefined ? ['--scenario', choice.scenarioPath] : []), ...(choice.force ? ['--force'] : [])];
  return new Promise((resolve, reject) => {
    const child = spawn(process.execPath, [BIN, 'replay', file, '--json', '--hashes', ...extra], { stdio: ['ignore', 'pipe', 'pipe'] });
    const out: Buffer[] = [];
    const err: Buffer[] = [];
    child.stdout.on('data', (b: Buffer) => out.push(b));
    child.stderr.on('data', (b: Buffer) => err.push(b));
    child.on('error', reject);
    child.on('close', (code) => {
      const stderr = Buffer.concat(err).toString('utf8').trim();
      let parsed: unknown = null;
      try {
        parsed = JSON.parse(Buffer.concat(out).toString('utf8'));
      } catch {
        parsed = null;
      }
      const result = parseReplayJson(parsed);
      if (result === null) reject(new Error(`replay process exited with code ${code}: ${stderr || 'no output'}`));
      else resolve(result);
    });
  });
}

/** Replays in a worker thread of this process (its own Jolt instance). */
function replayInWorker(file: string, choice: ScenarioChoice): Promise<RunResult> {
  return new Promise((resolve, reject) => {
    const worker = new Worker(siblingModuleUrl(import.meta.url, 'verify-worker'), { workerData: { file, ...choice } });
    let settled = false;
    worker.once('message', (msg: { ok: true; report: ReplayReport } | { ok: false; error: string }) => {
      settled = true;
      if (msg.ok) resolve({ status: msg.report.status, hashes: msg.report.hashes ?? [], msPerTick: msg.report.msPerTick, report: msg.report });
      else reject(new Error(msg.error));
    });
    worker.once('error', (e) => {
      settled = true;
      reject(e);
    });
    worker.once('exit', (code) => {
      if (!settled) reject(new Error(`replay worker exited with code ${code} before reporting`));
    });
  });
}

/** Runs `tasks` with at most `limit` in flight; results in task order. */
async function pool<T>(count: number, limit: number, task: (i: number) => Promise<T>): Promise<T[]> {
  const results: T[] = new Array(count);
  let next = 0;
  const lanes = Array.from({ length: Math.min(limit, count) }, async () => {
    while (next < count) {
      const i = next++;
      results[i] = await task(i);
    }
  });
  await Promise.all(lanes);
  return results;
}

/** The first tick counter at which two hash sequences differ, or -1. */
export function firstHashDifference(a: readonly string[], b: readonly string[]): number {
  const n = Math.min(a.length, b.length);
  for (let i = 0; i < n; i++) if (a[i] !== b[i]) return i;
  return a.length === b.length ? -1 : n;
}

async function run(args: ParsedArgs, io: CliIo): Promise<number> {
  const file = args.positionals[0];
  const runs = args.number('runs', 2);
  const workers = args.flag('workers');
  const mode = workers ? 'worker threads' : 'processes';
  try {
    const probe = await LogReader.open(file); // fail fast (and as a usage error) on a missing file
    await probe.close();
  } catch (err) {
    if ((err as NodeJS.ErrnoException).code === 'ENOENT') throw new UsageError(`no such file: ${file}`);
    throw err;
  }
  const limit = Math.max(1, Math.min(runs, availableParallelism()));
  const choice: ScenarioChoice = { force: args.flag('force') };
  const scenarioPath = args.string('scenario');
  if (scenarioPath !== undefined) {
    await scenarioFromArg(scenarioPath); // a missing or broken module is a usage error here, not N failed runs
    choice.scenarioPath = resolve(scenarioPath);
  }
  const results = await pool(runs, limit, () => (workers ? replayInWorker(file, choice) : replayInProcess(file, choice)));
  const ref = results[0];
  const problems: string[] = [];
  results.forEach((r, i) => {
    if (i === 0) return;
    const at = firstHashDifference(ref.hashes, r.hashes);
    if (at >= 0) {
      const theirs = r.hashes[at] ?? '(none: the run stopped)';
      problems.push(`run ${i + 1} differs from run 1 at tick ${at}: ${ref.hashes[at] ?? '(none)'} vs ${theirs}`);
    }
  });
  const logProblem = results.find((r) => r.status !== 'ok');
  const json = args.flag('json');
  const summary = {
    file,
    runs,
    mode,
    ticks: ref.hashes.length - 1,
    agree: problems.length === 0,
    matchesLog: logProblem === undefined,
    differences: problems,
    replay: logProblem ? { status: logProblem.report.status, divergence: logProblem.report.divergence ?? null, corruption: logProblem.report.corruption ?? null } : null,
    msPerTick: results.map((r) => r.msPerTick),
  };
  if (json) io.stdout(`${JSON.stringify(summary)}\n`);
  if (problems.length > 0 || logProblem) {
    if (!json) {
      for (const p of problems) io.stderr(`verify: ${p}\n`);
      if (logProblem) io.stderr(`verify: replay vs log: ${describeFailure(logProblem.report) ?? `${logProblem.status}\n`}`);
    }
    return ExitCode.Failed;
  }
  if (!json) io.stdout(`ok: ${runs} replays in separate ${mode} agree on all ${ref.hashes.length} state hashes (ticks 0–${ref.hashes.length - 1}) and match the log\n`);
  return ExitCode.Ok;
}

/** The verify command. */
export const verifyCommand: CommandSpec = {
  name: 'verify',
  summary: 'Replay a log in several processes (or threads) and compare their per-tick hashes',
  details: 'Each run replays the whole log in its own Jolt instance, hashing the state after every tick. Exit 1 if any two\nruns differ at any tick or a run disagrees with the hashes recorded in the log.',
  positionals: [{ name: 'FILE', description: 'input log to verify', required: true }],
  flags: [
    { name: 'runs', kind: 'int', valueName: 'N', description: 'independent replays (default 2)', min: 2, max: 64 },
    { name: 'workers', kind: 'boolean', description: 'use worker threads of this process instead of child processes' },
    { name: 'json', kind: 'boolean', description: 'print a JSON summary on stdout' },
    ...SCENARIO_MODULE_FLAGS,
  ],
  run,
};
