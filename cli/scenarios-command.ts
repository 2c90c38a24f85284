// `scenarios [--json]`: lists every registered scenario with its description and parameters (defaults, limits).
import type { ScenarioDefinition } from '../shared/sim/scenario.ts';
import type { ParsedArgs } from './args.ts';
import { ExitCode, type CliIo, type CommandSpec } from './command.ts';
import { allScenarios } from './scenario-setup.ts';

/** A scenario as plain JSON data (what `scenarios --json` prints for each). */
export function scenarioInfo(def: ScenarioDefinition): Record<string, unknown> {
  return {
    name: def.name,
    description: def.description,
    params: Object.fromEntries(
      Object.entries(def.params).map(([k, p]) => [k, { default: p.default, min: p.min, max: p.max, integer: p.integer === true, description: p.description }]),
    ),
    golden: { ticks: def.golden.ticks, bots: def.golden.bots },
  };
}

function describe(def: ScenarioDefinition): string {
  const lines = [`${def.name}`, `  ${def.description}`];
  const entries = Object.entries(def.params);
  if (entries.length === 0) lines.push('  (no parameters)');
  const width = Math.max(0, ...entries.map(([k]) => k.length));
  for (const [k, p] of entries) {
    const range = `[${p.min}, ${p.max}]${p.integer ? ' integer' : ''}`;
    lines.push(`  --param ${k.padEnd(width)}  default ${String(p.default).padEnd(6)} ${range.padEnd(22)} ${p.description}`);
  }
  return lines.join('\n');
}

async function run(args: ParsedArgs, io: CliIo): Promise<number> {
  const defs = allScenarios();
  if (args.flag('json')) io.stdout(`${JSON.stringify(defs.map(scenarioInfo))}\n`);
  else io.stdout(`${defs.map(describe).join('\n\n')}\n`);
  return ExitCode.Ok;
}

/** The scenarios command. */
export const scenariosCommand: CommandSpec = {
  name: 'scenarios',
  summary: 'List scenarios with their descriptions and parameters',
  positionals: [],
  flags: [{ name: 'json', kind: 'boolean', description: 'print a JSON array on stdout' }],
  run,
};
