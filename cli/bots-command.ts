// `bots --url ws://127.0.0.1:8080 --count N [--room ID] [--seconds S] [--seed SEED] [--predict [--scenario FILE]]`:
// headless scripted bots that join a running server through the client library and play until the time is up (or
// Ctrl+C), then report traffic (and, with --predict, their rollback numbers and desyncs).
import { startBots, type BotsReport } from './bots.ts';
import { nodePredictOptions } from './predict-options.ts';
import { scenarioFromArg } from './scenario-setup.ts';
import type { ParsedArgs } from './args.ts';
import { ExitCode, UsageError, type CliIo, type CommandSpec } from './command.ts';

function summary(r: BotsReport): string {
  const lines = [`${r.bots.length} bot(s) for ${r.seconds.toFixed(1)} s: ${r.kbpsInPerBot.toFixed(1)} kbps received per bot`];
  for (const b of r.bots) {
    const rtt = b.rttMs === null ? '-' : `${b.rttMs.toFixed(1)} ms`;
    lines.push(
      `  ${b.name}: ${b.connected ? `player ${b.playerId}` : 'never joined'}, ${b.snapshots} snapshots, ${(b.bytesIn / 1024).toFixed(1)} KiB in, ` +
        `${(b.bytesOut / 1024).toFixed(1)} KiB out, rtt ${rtt}, missed input ticks ${b.missedInputTicks ?? '-'}` +
        `${b.serverErrors ? `, ${b.serverErrors} server error(s)` : ''}${b.closedReason && b.closedReason !== 'client-closed' ? `, ended by the server: ${b.closedDetail ?? b.closedReason}` : ''}`,
    );
    const p = b.prediction;
    if (p) lines.push(`    ${p.mode}${p.reason ? ` (${p.reason})` : ''}: rollback p99 ${p.rollbackDepthP99} ticks, re-sim p99 ${p.resimMsP99.toFixed(2)} ms, ${p.corrections} corrections, ${p.desyncs} desyncs`);
  }
  return `${lines.join('\n')}\n`;
}

async function run(args: ParsedArgs, io: CliIo): Promise<number> {
  const url = args.string('url')!;
  if (!/^wss?:\/\/\S+$/.test(url)) throw new UsageError(`--url must be a ws:// or wss:// URL, got "${url}"`);
  const room = args.string('room') ?? null;
  if (room !== null && !/^[A-Za-z0-9_-]{1,64}$/.test(room)) throw new UsageError('--room must be 1-64 characters of A-Z a-z 0-9 _ -');
  const seconds = args.number('seconds') ?? null;
  const scenarioArg = args.string('scenario');
  if (scenarioArg !== undefined && !args.flag('predict')) throw new UsageError('--scenario is for --predict (the bots simulate that scenario themselves)');
  const own = scenarioArg === undefined ? [] : [await scenarioFromArg(scenarioArg)];
  const botsRun = startBots({
    url,
    count: args.number('count')!,
    room,
    seconds,
    seed: args.string('seed') ?? 1,
    predict: args.flag('predict') ? nodePredictOptions({}, own) : undefined,
    progress: (line) => io.stderr(`${line}\n`),
  });
  const onSignal = (): void => botsRun.stop();
  process.once('SIGINT', onSignal);
  process.once('SIGTERM', onSignal);
  try {
    const report = await botsRun.done;
    if (args.flag('json')) io.stdout(`${JSON.stringify(report)}\n`);
    else io.stdout(summary(report));
    const failed = report.bots.filter((b) => !b.connected || (b.closedReason !== null && b.closedReason !== 'client-closed'));
    if (failed.length > 0) {
      io.stderr(`${failed.length} bot(s) could not join or were disconnected: ${failed.map((b) => `${b.name} (${b.closedDetail ?? b.closedReason ?? 'no welcome'})`).join(', ')}\n`);
      return ExitCode.Failed;
    }
    return ExitCode.Ok;
  } finally {
    process.off('SIGINT', onSignal);
    process.off('SIGTERM', onSignal);
  }
}

/** The bots command. */
export const botsCommand: CommandSpec = {
  name: 'bots',
  summary: 'Run headless scripted bots against a server',
  details:
    'Each bot is a client of the client library with its own seeded script (walk, strafe, turn, sprint, jump, fire),\n' +
    'sending 60 commands per second. Without --seconds they run until Ctrl+C. Exit 1 if a bot could not join or was\n' +
    'disconnected by the server.',
  positionals: [],
  flags: [
    { name: 'url', kind: 'string', valueName: 'URL', description: 'server WebSocket URL, e.g. ws://127.0.0.1:8080', required: true },
    { name: 'count', kind: 'int', valueName: 'N', description: 'number of bots', required: true, min: 1, max: 1000 },
    { name: 'room', kind: 'string', valueName: 'ID', description: "room to join (a scenario name opens a room of it); default the server's default room" },
    { name: 'seconds', kind: 'number', valueName: 'S', description: 'stop after S seconds', min: 0.1, max: 86_400 },
    { name: 'seed', kind: 'string', valueName: 'SEED', description: 'seed of the bots’ scripts; default 1' },
    { name: 'json', kind: 'boolean', description: 'print the report as JSON' },
    { name: 'predict', kind: 'boolean', description: 'run the simulation in each bot (predicted play) where the room offers predict mode' },
    { name: 'scenario', kind: 'string', valueName: 'FILE', description: "with --predict: the room's scenario module (your own game); built-ins need none" },
  ],
  run,
};
