// `goldens [--write] [--scenario NAME] [--dir DIR]`: runs every scenario's scripted golden run (shared/sim/golden.ts)
// and checks the final hash against `<name>.golden.json`; only --write rewrites those files.
import { readFile, writeFile } from 'node:fs/promises';
import { join } from 'node:path';
import { fileURLToPath } from 'node:url';
import '../server/physics-node.ts';
import { formatGoldenFile, parseGoldenFile, runGolden, type GoldenResult } from '../shared/sim/golden.ts';
import { installedJoltVersion } from '../server/log/jolt-version.ts';
import type { ParsedArgs } from './args.ts';
import { ExitCode, type CliIo, type CommandSpec } from './command.ts';
import { allScenarios, scenarioNamed } from './scenario-setup.ts';

/** Where golden files live by default: beside the scenarios. */
export const DEFAULT_GOLDEN_DIR = fileURLToPath(new URL('../scenarios/', import.meta.url));

/** Compares a golden run with its stored file; returns null when they agree, else what differs. */
export async function checkGolden(result: GoldenResult, path: string): Promise<string | null> {
  let text: string;
  try {
    text = await readFile(path, 'utf8');
  } catch (err) {
    if ((err as NodeJS.ErrnoException).code === 'ENOENT') return `no golden file ${path} (create it with "goldens --write")`;
    throw err;
  }
  let raw: unknown;
  try {
    raw = JSON.parse(text);
  } catch (err) {
    return `${path} is not valid JSON: ${(err as Error).message}`;
  }
  const stored = parseGoldenFile(raw, path);
  if (stored.scenario !== result.scenario) return `${path} is the golden of "${stored.scenario}"`;
  if (stored.ticks !== result.ticks || stored.bots !== result.bots || stored.seed !== result.seed) {
    return `the golden script changed: stored ${stored.ticks} ticks / ${stored.bots} bots / seed ${stored.seed}, now ${result.ticks} / ${result.bots} / ${result.seed}`;
  }
  if (stored.hash !== result.hash) {
    const jolt = installedJoltVersion();
    const note = stored.joltVersion !== jolt ? ` (stored with jolt-physics ${stored.joltVersion}, running ${jolt})` : '';
    return `hash after ${result.ticks} ticks is ${result.hash}, golden says ${stored.hash}${note}`;
  }
  return null;
}

async function run(args: ParsedArgs, io: CliIo): Promise<number> {
  const only = args.string('scenario');
  const defs = only !== undefined ? [scenarioNamed(only)] : allScenarios();
  const dir = args.string('dir') ?? DEFAULT_GOLDEN_DIR;
  const write = args.flag('write');
  let failures = 0;
  for (const def of defs) {
    const t0 = performance.now();
    const result = await runGolden(def);
    const seconds = ((performance.now() - t0) / 1000).toFixed(1);
    const path = join(dir, `${def.name}.golden.json`);
    if (write) {
      await writeFile(path, formatGoldenFile(result, installedJoltVersion()));
      io.stdout(`wrote   ${def.name.padEnd(18)} ${result.hash}  ${result.ticks} ticks, ${result.bots} bots (${seconds} s) → ${path}\n`);
      continue;
    }
    const problem = await checkGolden(result, path);
    if (problem === null) io.stdout(`ok      ${def.name.padEnd(18)} ${result.hash}  ${result.ticks} ticks, ${result.bots} bots (${seconds} s)\n`);
    else {
      failures++;
      io.stdout(`FAILED  ${def.name.padEnd(18)} ${problem}\n`);
    }
  }
  if (failures > 0) {
    io.stderr(`goldens: ${failures} of ${defs.length} scenario(s) differ from their golden; if the change is intended, run "goldens --write" and commit the files\n`);
    return ExitCode.Failed;
  }
  return ExitCode.Ok;
}

/** The goldens command. */
export const goldensCommand: CommandSpec = {
  name: 'goldens',
  summary: "Check (or with --write, rewrite) every scenario's golden state hash",
  details: 'A golden run is the scenario\'s scripted bots at the fixed golden seed for its golden tick count\n(shared/sim/golden.ts). Without --write nothing is written; exit 1 if any hash differs or a file is missing.',
  positionals: [],
  flags: [
    { name: 'write', kind: 'boolean', description: 'rewrite the golden files with the hashes of this build' },
    { name: 'scenario', kind: 'string', valueName: 'NAME', description: 'only this scenario' },
    { name: 'dir', kind: 'string', valueName: 'DIR', description: 'folder of the <name>.golden.json files (default: scenarios/)' },
  ],
  run,
};
