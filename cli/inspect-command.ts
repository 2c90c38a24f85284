// `inspect FILE [--json]`: what an input log holds without simulating it: header, record counts and bytes by type,
// session length, its checkpoints, and how the file ends (complete, unterminated, truncated, or where it is corrupt).
import { LogCorruptError, type LogEntry } from '../server/log/log-format.ts';
import { LogReader } from '../server/log/log-reader.ts';
import type { ParsedArgs } from './args.ts';
import { ExitCode, UsageError, type CliIo, type CommandSpec } from './command.ts';

/** Checkpoint ticks (with their time of play), the first and last few when there are many. */
function describeCheckpoints(list: ReadonlyArray<{ tick: number }>, tickRateHz: number): string {
  if (list.length === 0) return 'none (replay --from and resume start at tick 0)';
  const show = (c: { tick: number }): string => `${c.tick} (${(c.tick / tickRateHz).toFixed(1)} s)`;
  const shown = list.length <= 12 ? list.map(show) : [...list.slice(0, 5).map(show), `… ${list.length - 10} more …`, ...list.slice(-5).map(show)];
  return `${list.length} at tick ${shown.join(', ')}`;
}

async function run(args: ParsedArgs, io: CliIo): Promise<number> {
  const file = args.positionals[0];
  let reader: LogReader;
  try {
    reader = await LogReader.open(file);
  } catch (err) {
    if ((err as NodeJS.ErrnoException).code === 'ENOENT') throw new UsageError(`no such file: ${file}`);
    throw err;
  }
  const counts: Record<LogEntry['type'], { records: number; bytes: number }> = {
    tick: { records: 0, bytes: 0 },
    hash: { records: 0, bytes: 0 },
    checkpoint: { records: 0, bytes: 0 },
    end: { records: 0, bytes: 0 },
  };
  const checkpoints: Array<{ tick: number; recordIndex: number; byteOffset: number; sizeBytes: number }> = [];
  let players = 0;
  let maxPlayers = 0;
  try {
    for await (const e of reader.entries()) {
      counts[e.type].records++;
      counts[e.type].bytes += e.sizeBytes;
      if (e.type === 'checkpoint') checkpoints.push({ tick: e.tick, recordIndex: e.index, byteOffset: e.offset, sizeBytes: e.sizeBytes });
      if (e.type === 'tick') {
        players += e.record.joins.length - e.record.leaves.length;
        maxPlayers = Math.max(maxPlayers, players);
      }
    }
  } catch (err) {
    if (!(err instanceof LogCorruptError)) throw err;
  } finally {
    await reader.close();
  }
  const h = reader.header;
  const o = reader.outcome!;
  const ticks = counts.tick.records;
  const info = {
    file,
    header: h,
    status: o.status,
    ticks,
    seconds: ticks / h.tickRateHz,
    maxPlayers,
    fileBytes: o.fileBytes,
    bytesPerTick: ticks > 0 ? o.fileBytes / ticks : 0,
    records: counts,
    checkpoints,
    corruption: o.corruption ?? null,
  };
  if (args.flag('json')) io.stdout(`${JSON.stringify(info)}\n`);
  else {
    const lines = [
      `${file}: input log v${h.formatVersion}, ${h.scenario} (seed ${JSON.stringify(h.seed)}), jolt-physics ${h.joltVersion}, by ${h.createdBy || '?'}`,
      `  params: ${Object.entries(h.params).map(([k, v]) => `${k}=${v}`).join(' ') || '(none)'}`,
      ...(h.scenarioHash ? [`  scenario module: ${h.scenarioHash} (replay and verify need that module: --scenario FILE)`] : []),
      `  ${ticks} ticks (${info.seconds.toFixed(1)} s at ${h.tickRateHz} Hz), up to ${maxPlayers} players, ${o.fileBytes} bytes (${info.bytesPerTick.toFixed(1)} bytes/tick)`,
      `  hash every ${h.hashEveryTicks || '-'} ticks, checkpoint every ${h.checkpointEveryTicks || '-'} ticks`,
      ...Object.entries(counts).map(([type, c]) => `  ${type.padEnd(10)} ${String(c.records).padStart(8)} records ${String(c.bytes).padStart(12)} bytes`),
      `  checkpoints: ${describeCheckpoints(checkpoints, h.tickRateHz)}`,
      `  status: ${o.status}${o.corruption ? ` at record #${o.corruption.recordIndex} (byte offset ${o.corruption.byteOffset}): ${o.corruption.reason}` : ''}${o.status === 'truncated' ? ` (${o.fileBytes - o.validBytes} bytes of a partial record at the end)` : ''}`,
    ];
    io.stdout(`${lines.join('\n')}\n`);
  }
  return o.status === 'corrupt' ? ExitCode.Failed : ExitCode.Ok;
}

/** The inspect command. */
export const inspectCommand: CommandSpec = {
  name: 'inspect',
  summary: 'Show what an input log holds (header, records, sizes, integrity) without simulating',
  details: 'Reads every record and checks every CRC; exit 1 if the log is corrupt (a truncated tail is not an error).',
  positionals: [{ name: 'FILE', description: 'input log to read', required: true }],
  flags: [{ name: 'json', kind: 'boolean', description: 'print one JSON object on stdout' }],
  run,
};
