// Where an interrupted input log can be resumed: reads a log file whole, checks every record (framing, CRC, order),
// and finds the last intact record and the last checkpoint before it. Damage at the tail (a torn last write: no
// intact record follows it) is cut off; damage with intact records after it is refused, naming the record. No
// simulation here: server/resume-rooms.ts re-simulates from the checkpoint and checks the hashes.
import { readFile } from 'node:fs/promises';
import type { TickInputRecord } from '../../shared/sim/types.ts';
import { scanFrame } from './frame.ts';
import { readLogBytes } from './log-bytes.ts';
import { LogFormatError, type LogEntry, type LogHeader } from './log-format.ts';

/** An interrupted log that can go on: everything before `validBytes` is intact. */
export interface ResumePoint {
  path: string;
  header: LogHeader;
  /** Tick records in the intact prefix = the tick counter the room resumes at. */
  ticks: number;
  /** Bytes of the intact prefix (the writer cuts the file here and appends). */
  validBytes: number;
  fileBytes: number;
  /** How the file ended: a clean end between records, a partial last record, or a damaged tail. */
  ending: 'unterminated' | 'truncated' | 'damaged-tail';
  /** What was wrong with the tail (damaged-tail only). */
  tailDamage?: string;
  /** The last checkpoint in the prefix (null: re-simulate from tick 0). */
  checkpoint: { tick: number; bytes: Uint8Array; index: number } | null;
  /** Hash records of the prefix, by tick counter (for checking the re-simulation). */
  hashes: Map<number, { hash: string; index: number; offset: number }>;
  /** Tick records after the checkpoint (all of them without one), in order. */
  records: TickInputRecord[];
  /** Every player's name by id, from the joins of the whole prefix. */
  names: Map<number, string>;
  /** The largest player id ever joined (0: none). */
  maxPlayerId: number;
}

/** Why a log is not resumed. `complete` logs ended cleanly and are skipped without complaint. */
export type ResumeRefusal = { path: string; kind: 'complete' } | { path: string; kind: 'refused'; reason: string; recordIndex?: number; byteOffset?: number };

/** The first offset after `from` where an intact record starts, or -1. */
function nextIntactRecord(bytes: Uint8Array, from: number): number {
  for (let at = from + 1; at < bytes.length; at++) if (scanFrame(bytes, at, bytes.length).kind === 'frame') return at;
  return -1;
}

/**
 * Reads and checks one log; a ResumePoint when it can be resumed, else why not. Never throws for a bad file.
 * `onTick` sees every tick record of the intact prefix, in order.
 */
export async function findResumePoint(path: string, onTick?: (record: TickInputRecord) => void): Promise<ResumePoint | ResumeRefusal> {
  let bytes: Uint8Array;
  try {
    bytes = new Uint8Array(await readFile(path));
  } catch (err) {
    return { path, kind: 'refused', reason: `cannot read it: ${(err as Error).message}` };
  }
  let log;
  try {
    log = readLogBytes(bytes, path);
  } catch (err) {
    if (err instanceof LogFormatError) return { path, kind: 'refused', reason: err.message };
    throw err;
  }
  const o = log.outcome;
  if (o.status === 'complete') return { path, kind: 'complete' };
  let ending: ResumePoint['ending'] = o.status === 'truncated' ? 'truncated' : 'unterminated';
  let tailDamage: string | undefined;
  if (o.status === 'corrupt') {
    const c = o.corruption!;
    const intact = nextIntactRecord(bytes, c.byteOffset);
    if (intact >= 0) {
      return { path, kind: 'refused', reason: `record #${c.recordIndex} (byte offset ${c.byteOffset}) is damaged and intact records follow it (byte offset ${intact}): ${c.reason}`, recordIndex: c.recordIndex, byteOffset: c.byteOffset };
    }
    ending = 'damaged-tail';
    tailDamage = `record #${c.recordIndex} (byte offset ${c.byteOffset}) and the ${o.fileBytes - c.byteOffset} bytes after it: ${c.reason}`;
  }
  return { path, header: log.header, ticks: o.ticks, validBytes: o.validBytes, fileBytes: o.fileBytes, ending, ...(tailDamage ? { tailDamage } : {}), ...collect(log.entries, onTick) };
}

function collect(entries: readonly LogEntry[], onTick: ((record: TickInputRecord) => void) | undefined): Pick<ResumePoint, 'checkpoint' | 'hashes' | 'records' | 'names' | 'maxPlayerId'> {
  let checkpoint: ResumePoint['checkpoint'] = null;
  const hashes: ResumePoint['hashes'] = new Map();
  let records: TickInputRecord[] = [];
  const names = new Map<number, string>();
  let maxPlayerId = 0;
  for (const e of entries) {
    if (e.type === 'tick') {
      records.push(e.record);
      onTick?.(e.record);
      for (const j of e.record.joins) {
        names.set(j.playerId, j.name);
        maxPlayerId = Math.max(maxPlayerId, j.playerId);
      }
    } else if (e.type === 'hash') hashes.set(e.tick, { hash: e.hash, index: e.index, offset: e.offset });
    else if (e.type === 'checkpoint') {
      checkpoint = { tick: e.tick, bytes: e.bytes, index: e.index };
      records = [];
    }
  }
  return { checkpoint, hashes, records, names, maxPlayerId };
}
