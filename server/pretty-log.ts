// Human-readable log lines for a terminal: turns each of pino's JSON lines into
// `HH:MM:SS.mmm LEVEL message key=value …` (UTC time, level coloured when asked) and writes it synchronously.
// The JSON stays the format for files, pipes and `--log-format json`.
import { writeSync } from 'node:fs';

/** The log line formats `serve` offers. */
export const LogFormat = { Json: 'json', Pretty: 'pretty' } as const;
export type LogFormat = (typeof LogFormat)[keyof typeof LogFormat];

const LEVELS: Readonly<Record<number, { name: string; colour: string }>> = {
  10: { name: 'TRACE', colour: '\x1b[90m' },
  20: { name: 'DEBUG', colour: '\x1b[36m' },
  30: { name: 'INFO ', colour: '\x1b[32m' },
  40: { name: 'WARN ', colour: '\x1b[33m' },
  50: { name: 'ERROR', colour: '\x1b[31m' },
  60: { name: 'FATAL', colour: '\x1b[35m' },
};
const RESET = '\x1b[0m';
// Fields every line carries that a terminal reader does not need.
const SKIPPED = new Set(['level', 'time', 'msg', 'pid', 'hostname', 'service']);

function value(v: unknown): string {
  if (typeof v === 'string') return /^[^\s"=]+$/.test(v) ? v : JSON.stringify(v);
  if (v !== null && typeof v === 'object') {
    const err = v as { type?: unknown; message?: unknown; stack?: unknown };
    if (typeof err.message === 'string' && typeof err.stack === 'string') return `${JSON.stringify(err.message)}\n${err.stack}`;
  }
  return JSON.stringify(v) ?? String(v);
}

/** One pino JSON line as a human-readable line (a line that is not JSON comes back unchanged). */
export function prettyLogLine(jsonLine: string, colour: boolean): string {
  let rec: Record<string, unknown>;
  try {
    rec = JSON.parse(jsonLine) as Record<string, unknown>;
  } catch {
    return jsonLine.endsWith('\n') ? jsonLine : `${jsonLine}\n`;
  }
  const time = typeof rec.time === 'number' ? new Date(rec.time).toISOString().slice(11, 23) : '--:--:--.---';
  const level = LEVELS[rec.level as number] ?? { name: String(rec.level).padEnd(5), colour: '' };
  const levelText = colour && level.colour ? `${level.colour}${level.name}${RESET}` : level.name;
  const fields = Object.keys(rec)
    .filter((k) => !SKIPPED.has(k))
    .map((k) => `${k}=${value(rec[k])}`);
  const msg = typeof rec.msg === 'string' ? rec.msg : '';
  return `${time} ${levelText} ${msg}${fields.length ? `  ${fields.join(' ')}` : ''}\n`;
}

/** A pino destination that writes pretty lines to a file descriptor, synchronously (nothing is lost at exit). */
export function prettyDestination(fd: number, colour: boolean): { write(line: string): void; flush(cb: () => void): void } {
  return {
    write(line: string): void {
      writeSync(fd, prettyLogLine(line, colour));
    },
    flush(cb: () => void): void {
      cb();
    },
  };
}
