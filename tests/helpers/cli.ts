// Test helpers for the CLI: run main() in-process with captured stdout/stderr, and tamper with input logs.
import { main } from '../../cli/main.ts';
import { readLogBytes } from '../../server/log/log-bytes.ts';
import { LogEncoder } from '../../server/log/log-encoder.ts';
import type { TickInputRecord } from '../../shared/sim/types.ts';

/** What one CLI invocation produced. */
export interface CliResult {
  code: number;
  stdout: string;
  stderr: string;
}

/** Runs the CLI in this process (stderr not a TTY) and captures its output. */
export async function cli(...argv: string[]): Promise<CliResult> {
  let stdout = '';
  let stderr = '';
  const code = await main(argv, { stdout: (t) => void (stdout += t), stderr: (t) => void (stderr += t), stderrIsTTY: false });
  return { code, stdout, stderr };
}

/** Parses the single JSON line a --json command printed. */
export function jsonOut(r: CliResult): Record<string, unknown> {
  const lines = r.stdout.trim().split('\n');
  if (lines.length !== 1) throw new Error(`expected one JSON line, got ${lines.length}: ${r.stdout}\n${r.stderr}`);
  return JSON.parse(lines[0]) as Record<string, unknown>;
}

/**
 * Rewrites the tick record for `tick` with `edit` applied, re-framed with a valid CRC: a well-formed log whose
 * inputs no longer match its recorded hashes. Returns the new bytes.
 */
export function retouchTick(log: Uint8Array, tick: number, edit: (rec: TickInputRecord) => void): Uint8Array {
  const { header, entries } = readLogBytes(log);
  const e = entries.find((x) => x.type === 'tick' && x.record.tick === tick);
  if (!e || e.type !== 'tick') throw new Error(`no tick record for tick ${tick}`);
  const rec = structuredClone(e.record);
  edit(rec);
  const enc = new LogEncoder(header);
  enc.ticks = tick;
  const frame = enc.tick(rec);
  const out = new Uint8Array(log.length - e.sizeBytes + frame.length);
  out.set(log.subarray(0, e.offset), 0);
  out.set(frame, e.offset);
  out.set(log.subarray(e.offset + e.sizeBytes), e.offset + frame.length);
  return out;
}
