// `run --scenario NAME [--ticks N] [--param k=v]… [--seed S] [--bots N] [--json]`: a headless run that prints the
// final state hash and the mean simulation time per tick.
import { BotScript } from '../shared/sim/bots.ts';
import { emptyTickInput } from '../shared/sim/types.ts';
import type { ParsedArgs } from './args.ts';
import { ExitCode, type CliIo, type CommandSpec } from './command.ts';
import { ProgressBar } from './progress.ts';
import { createSimulation, parseSeed, scenarioFromArg } from './scenario-setup.ts';

/** Default length of a headless run: ten seconds of play. */
export const DEFAULT_RUN_TICKS = 600;

async function run(args: ParsedArgs, io: CliIo): Promise<number> {
  const def = await scenarioFromArg(args.string('scenario')!);
  const params = args.pairs('param');
  const seed = parseSeed(args.string('seed'));
  const ticks = args.number('ticks', DEFAULT_RUN_TICKS);
  const botCount = args.number('bots', 0);
  const sim = await createSimulation(def, params, seed);
  const bar = new ProgressBar(io, 'run');
  try {
    const bots = botCount > 0 ? new BotScript({ seed, bots: botCount }) : null;
    let stepMs = 0;
    for (let t = 0; t < ticks; t++) {
      const record = bots ? bots.next() : emptyTickInput(t);
      const t0 = performance.now();
      sim.step(record);
      stepMs += performance.now() - t0;
      bar.update((t + 1) / ticks, `tick ${t + 1}/${ticks}`);
    }
    bar.clear();
    const hash = sim.stateHash();
    const msPerTick = ticks > 0 ? stepMs / ticks : 0;
    if (args.flag('json')) io.stdout(`${JSON.stringify({ scenario: def.name, ticks, hash, msPerTick })}\n`);
    else io.stdout(`${def.name}: ${ticks} ticks, final hash ${hash} (${msPerTick.toFixed(3)} ms/tick)\n`);
    return ExitCode.Ok;
  } finally {
    sim.destroy();
  }
}

/** The run command. */
export const runCommand: CommandSpec = {
  name: 'run',
  summary: 'Run a scenario headless and print its final state hash',
  details: 'Without --bots every tick is empty (no players). msPerTick is the mean time of Simulation.step.',
  positionals: [],
  flags: [
    { name: 'scenario', kind: 'string', valueName: 'NAME|FILE', description: 'scenario to run: a built-in name (see "scenarios") or a module file', required: true },
    { name: 'ticks', kind: 'int', valueName: 'N', description: `ticks to simulate (default ${DEFAULT_RUN_TICKS})`, min: 0, max: 100_000_000 },
    { name: 'param', kind: 'pair', valueName: 'k=v', description: 'scenario parameter (repeatable)' },
    { name: 'seed', kind: 'string', valueName: 'S', description: 'PRNG seed: an integer in [0, 2^32) or a word (default 1)' },
    { name: 'bots', kind: 'int', valueName: 'N', description: 'scripted bots driving characters (default 0)', min: 0, max: 10_000 },
    { name: 'json', kind: 'boolean', description: 'print {"scenario","ticks","hash","msPerTick"} on stdout' },
  ],
  run,
};
