// `record --scenario NAME --bots N --ticks T --out FILE …`: seeded scripted bots (walk, jump, fire) drive
// characters while every tick's inputs, hashes and periodic checkpoints are written to an input log.
import { BotScript } from '../shared/sim/bots.ts';
import { SessionLog } from '../server/log/session-log.ts';
import { scenarioModuleHash } from '../server/scenario-module.ts';
import type { ParsedArgs } from './args.ts';
import { ExitCode, UsageError, type CliIo, type CommandSpec } from './command.ts';
import { ProgressBar } from './progress.ts';
import { createSimulation, parseSeed, scenarioFromArg } from './scenario-setup.ts';
import { PROGRAM } from './usage.ts';

/** Default checkpoint interval of recorded logs (ticks). */
export const DEFAULT_CHECKPOINT_EVERY = 600;
/** Ticks between two waits for the log's queued writes (and progress-bar updates) while recording. */
const SETTLE_EVERY_TICKS = 60;

async function run(args: ParsedArgs, io: CliIo): Promise<number> {
  const def = await scenarioFromArg(args.string('scenario')!);
  const params = args.pairs('param');
  const seed = parseSeed(args.string('seed'));
  const ticks = args.number('ticks')!;
  const botCount = args.number('bots')!;
  const out = args.string('out')!;
  if (out === '') throw new UsageError('--out must name a file');
  const sim = await createSimulation(def, params, seed);
  const bar = new ProgressBar(io, 'record');
  let session: SessionLog | null = null;
  let closed = false;
  try {
    try {
      session = await SessionLog.create(out, sim, {
        hashEveryTicks: args.number('hash-every', 1),
        checkpointEveryTicks: args.number('checkpoint-every', DEFAULT_CHECKPOINT_EVERY),
        createdBy: `${PROGRAM} record --bots ${botCount}`,
        scenarioHash: await scenarioModuleHash(def),
        overwrite: args.flag('force'),
      });
    } catch (err) {
      if (/already exists/.test((err as Error).message)) throw new UsageError(`${out} already exists (pass --force to replace it)`);
      throw err;
    }
    const log: SessionLog = session;
    const bots = new BotScript({ seed, bots: botCount });
    const t0 = performance.now();
    for (let t = 0; t < ticks; t++) {
      log.step(bots.next());
      if (t % SETTLE_EVERY_TICKS === SETTLE_EVERY_TICKS - 1) {
        await log.writer.settled(); // lets queued writes reach the file: memory stays bounded
        bar.update((t + 1) / ticks, `tick ${t + 1}/${ticks}`);
      }
    }
    closed = true;
    await log.close();
    bar.clear();
    const wallMs = performance.now() - t0;
    const sizeBytes = log.writer.bytesWritten;
    const summary = { file: out, scenario: def.name, ticks, bots: botCount, hash: sim.stateHash(), sizeBytes, bytesPerTick: ticks > 0 ? sizeBytes / ticks : 0, msPerTick: ticks > 0 ? wallMs / ticks : 0 };
    if (args.flag('json')) io.stdout(`${JSON.stringify(summary)}\n`);
    else {
      io.stdout(
        `recorded ${ticks} ticks of ${def.name} with ${botCount} bot(s) to ${out}: ${sizeBytes} bytes ` +
          `(${summary.bytesPerTick.toFixed(1)} bytes/tick), final hash ${summary.hash}\n`,
      );
    }
    return ExitCode.Ok;
  } finally {
    bar.clear();
    if (session && !closed) await session.writer.abandon().catch(() => undefined); // keeps what was recorded
    sim.destroy();
  }
}

/** The record command. */
export const recordCommand: CommandSpec = {
  name: 'record',
  summary: 'Record a session of scripted bots into an input log',
  details:
    'Bots are seeded from --seed (as is the simulation): the same command line writes a byte-identical log.\n' +
    'A hash record follows every K-th tick (0: none) and a checkpoint every C-th tick (0: none); see docs/input-log.md.',
  positionals: [],
  flags: [
    { name: 'scenario', kind: 'string', valueName: 'NAME|FILE', description: 'scenario to record: a built-in name or a module file', required: true },
    { name: 'bots', kind: 'int', valueName: 'N', description: 'scripted bots (they join 10 ticks apart)', required: true, min: 0, max: 10_000 },
    { name: 'ticks', kind: 'int', valueName: 'T', description: 'ticks to record', required: true, min: 0, max: 100_000_000 },
    { name: 'out', kind: 'string', valueName: 'FILE', description: 'log file to create', required: true },
    { name: 'seed', kind: 'string', valueName: 'S', description: 'seed of simulation and bots: integer in [0, 2^32) or a word (default 1)' },
    { name: 'param', kind: 'pair', valueName: 'k=v', description: 'scenario parameter (repeatable)' },
    { name: 'hash-every', kind: 'int', valueName: 'K', description: 'ticks between hash records (default 1)', min: 0, max: 0xffffffff },
    { name: 'checkpoint-every', kind: 'int', valueName: 'C', description: `ticks between checkpoints (default ${DEFAULT_CHECKPOINT_EVERY})`, min: 0, max: 0xffffffff },
    { name: 'force', kind: 'boolean', description: 'replace FILE if it exists' },
    { name: 'json', kind: 'boolean', description: 'print a JSON summary on stdout' },
  ],
  run,
};
