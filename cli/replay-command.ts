// `replay FILE [--from TICK] [--to TICK] [--json] [--hashes]`: re-simulates an input log, checks every recorded hash, and on a
// mismatch names the first divergent tick and the first differing body (exit 1). Corrupt logs exit 1 too.
import { ExitCode, UsageError, type CliIo, type CommandSpec } from './command.ts';
import { ProgressBar } from './progress.ts';
import { replayLog, type ReplayReport } from './replay-session.ts';
import type { ParsedArgs } from './args.ts';
import { scenarioFromArg } from './scenario-setup.ts';
import type { FlagSpec } from './command.ts';

/** replay's and verify's flags for a log of a game's own scenario. */
export const SCENARIO_MODULE_FLAGS: readonly FlagSpec[] = [
  { name: 'scenario', kind: 'string', valueName: 'FILE', description: "the scenario's module, for a log of a scenario that is not built in" },
  { name: 'force', kind: 'boolean', description: "replay even if the scenario's module differs from the one recorded (hashes may differ)" },
];

/** Reads a log file for a command, turning a missing file into a usage error. */
export async function replayFile(file: string, run: () => Promise<ReplayReport>): Promise<ReplayReport> {
  try {
    return await run();
  } catch (err) {
    const e = err as NodeJS.ErrnoException;
    if (e.code === 'ENOENT') throw new UsageError(`no such file: ${file}`);
    if (e.code === 'EISDIR') throw new UsageError(`${file} is a directory, not an input log`);
    throw err;
  }
}

/** What describing a replay's verdict needs: the report, or what `replay --json` printed of it (verify's children). */
export type ReplayVerdict = Pick<ReplayReport, 'status' | 'ticks' | 'hashesChecked' | 'divergence' | 'corruption' | 'joltVersionNote' | 'scenarioNote'>;

/** The lines naming where a diverged or corrupt replay went wrong (tick, body, record, byte offset); null when ok. */
export function describeFailure(r: ReplayVerdict): string | null {
  const lines: string[] = [];
  if (r.joltVersionNote) lines.push(`warning: ${r.joltVersionNote}`);
  if (r.scenarioNote) lines.push(`warning: ${r.scenarioNote}`);
  if (r.status === 'diverged' && r.divergence) {
    const d = r.divergence;
    lines.push(`DIVERGED at tick ${d.tick} (after applying tick record ${d.tick - 1}): the log says ${d.expected}, the replay computed ${d.actual}`);
    lines.push(`  mismatching record: #${d.recordIndex} at byte offset ${d.byteOffset}; ${r.hashesChecked - 1} recorded hashes matched before it`);
    if (d.state) {
      const who =
        d.state.bodyId !== undefined ? `body ${d.state.bodyId}${d.state.body ? `, ${d.state.body}` : ''}` : d.state.playerId !== undefined ? `player ${d.state.playerId}` : d.state.part;
      lines.push(`  first difference (${who}) against the recorded checkpoint at tick ${d.state.checkpointTick}: ${d.state.detail}`);
    } else if (d.stateNote) lines.push(`  ${d.stateNote}`);
    return lines.join('\n') + '\n';
  }
  if (r.status === 'corrupt' && r.corruption) {
    const c = r.corruption;
    lines.push(`CORRUPT LOG at record #${c.recordIndex} (byte offset ${c.byteOffset}): ${c.reason}`);
    lines.push(`  the ${r.ticks} ticks before it replayed and all ${r.hashesChecked} recorded hashes matched`);
    return lines.join('\n') + '\n';
  }
  return null;
}

/** The human-readable summary of a replay (several lines). */
export function describeReplay(r: ReplayReport): string {
  const failure = describeFailure(r);
  if (failure !== null) return failure;
  const lines: string[] = [];
  if (r.joltVersionNote) lines.push(`warning: ${r.joltVersionNote}`);
  if (r.scenarioNote) lines.push(`warning: ${r.scenarioNote}`);
  const from = r.startTick > 0 ? ` from the checkpoint at tick ${r.startTick}` : '';
  lines.push(`ok: ${r.ticks} ticks${from} of ${r.header.scenario} (seed ${JSON.stringify(r.header.seed)}) replayed, ${r.hashesChecked} recorded hashes match, final hash ${r.finalHash} (${r.msPerTick.toFixed(3)} ms/tick)`);
  if (r.log === 'truncated') lines.push(`note: the log ends in a partial record (${r.droppedBytes} bytes, a crash while writing): the whole records before it were replayed`);
  if (r.log === 'unterminated') lines.push('note: the log has no end record (the recorder did not close it: a crash, or still recording)');
  return lines.join('\n') + '\n';
}

/** The JSON form of a replay (stable field order). */
export function replayJson(r: ReplayReport, withHashes: boolean): Record<string, unknown> {
  const out: Record<string, unknown> = {
    file: r.file,
    scenario: r.header.scenario,
    status: r.status,
    log: r.log,
    startTick: r.startTick,
    ticks: r.ticks,
    hashesChecked: r.hashesChecked,
    finalHash: r.finalHash,
    msPerTick: r.msPerTick,
    divergence: r.divergence ?? null,
    corruption: r.corruption ?? null,
  };
  const warnings = [r.joltVersionNote, r.scenarioNote].filter((w) => w !== undefined);
  if (warnings.length > 0) out.warning = warnings.join('; ');
  if (withHashes) out.hashes = r.hashes ?? [];
  return out;
}

async function run(args: ParsedArgs, io: CliIo): Promise<number> {
  const file = args.positionals[0];
  const toTick = args.number('to');
  const fromTick = args.number('from');
  if (fromTick !== undefined && args.flag('hashes')) throw new UsageError('--from and --hashes do not go together (hashes start at tick 0)');
  if (fromTick !== undefined && toTick !== undefined && toTick < fromTick) throw new UsageError(`--to ${toTick} is before --from ${fromTick}`);
  const json = args.flag('json');
  const bar = new ProgressBar(io, 'replay');
  const scenarioArg = args.string('scenario');
  const scenario = scenarioArg === undefined ? undefined : await scenarioFromArg(scenarioArg);
  const report = await replayFile(file, () =>
    replayLog(file, {
      ...(scenario !== undefined ? { scenario } : {}),
      force: args.flag('force'),
      ...(toTick !== undefined ? { toTick } : {}),
      ...(fromTick !== undefined ? { fromTick } : {}),
      collectHashes: args.flag('hashes'),
      onProgress: (f, tick) => bar.update(f, `tick ${tick}`),
    }),
  );
  bar.clear();
  if (json) io.stdout(`${JSON.stringify(replayJson(report, args.flag('hashes')))}\n`);
  else {
    const text = describeReplay(report);
    if (report.status === 'ok') io.stdout(text);
    else io.stderr(text);
    if (fromTick !== undefined) io.stderr(report.startTick > 0 ? `note: started from the checkpoint at tick ${report.startTick} (--from ${fromTick})\n` : `note: no checkpoint at or before tick ${fromTick}: replayed from tick 0\n`);
    if (toTick !== undefined && report.startTick + report.ticks < toTick) io.stderr(`note: --to ${toTick}, but the log holds only ${report.startTick + report.ticks} ticks\n`);
  }
  return report.status === 'ok' ? ExitCode.Ok : ExitCode.Failed;
}

/** The replay command. */
export const replayCommand: CommandSpec = {
  name: 'replay',
  summary: 'Re-simulate an input log and check every recorded state hash',
  details:
    'Stops at the first hash mismatch, names the divergent tick and the first differing body (from the next recorded\n' +
    'checkpoint), and exits 1; a corrupt log also exits 1 after replaying everything before the damage. A truncated\n' +
    'log (crash while recording) replays its whole records and exits 0. Progress goes to stderr when it is a terminal.',
  positionals: [{ name: 'FILE', description: 'input log (.taoslog) to replay', required: true }],
  flags: [
    { name: 'to', kind: 'int', valueName: 'TICK', description: 'stop once TICK ticks are applied', min: 0 },
    { name: 'from', kind: 'int', valueName: 'TICK', description: 'start from the last recorded checkpoint at or before TICK (hashes before it are not checked)', min: 0 },
    { name: 'json', kind: 'boolean', description: 'print one JSON object on stdout' },
    { name: 'hashes', kind: 'boolean', description: 'with --json: include the state hash at every tick (used by verify)' },
    ...SCENARIO_MODULE_FLAGS,
  ],
  run,
};
