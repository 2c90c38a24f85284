// The input log's reading rules, independent of where bytes come from: prelude checks, then record after record
// (framing, payload decoding, ordering: header first, consecutive ticks, hashes/checkpoints at the current tick,
// nothing after the end record). Used by the streaming file reader and the in-memory reader.
import { PayloadError } from '../../shared/byte-io.ts';
import { scanFrame } from './frame.ts';
import { LOG_MAGIC, READABLE_LOG_VERSIONS, LogCorruptError, LogFormatError, PRELUDE_BYTES, RECORD_TYPE_NAMES, RecordType, type LogEntry, type LogHeader, type RecordTypeCode } from './log-format.ts';
import { decodeCheckpoint, decodeEnd, decodeHash, decodeHeader, decodeTick } from './record-codec.ts';

/** Checks the 12-byte prelude and returns the format version; throws LogFormatError on anything else. */
export function checkPrelude(bytes: Uint8Array, available: number, source: string): number {
  const n = Math.min(available, LOG_MAGIC.length);
  for (let i = 0; i < n; i++) {
    if (bytes[i] !== LOG_MAGIC[i]) throw new LogFormatError(`${source} is not a taos-physics input log (bad magic bytes)`);
  }
  if (available < PRELUDE_BYTES) {
    throw new LogFormatError(available === 0 ? `${source} is empty` : `${source} is truncated inside its ${PRELUDE_BYTES}-byte prelude (${available} bytes)`);
  }
  const version = bytes[8] | (bytes[9] << 8);
  if (!READABLE_LOG_VERSIONS.includes(version)) {
    throw new LogFormatError(`${source} has input log format version ${version}; this build reads versions ${READABLE_LOG_VERSIONS.join(' and ')}`);
  }
  const flags = bytes[10] | (bytes[11] << 8);
  if (flags !== 0) throw new LogFormatError(`${source} sets unknown prelude flags 0x${flags.toString(16)}`);
  return version;
}

/** Result of offering bytes to the parser: one record, or more bytes needed. */
export type ParseStep = { kind: 'header'; header: LogHeader; frameEnd: number } | { kind: 'entry'; entry: LogEntry; frameEnd: number } | { kind: 'need'; totalBytes: number };

/** Stateful record-by-record reader of a log's records (after the prelude). */
export class LogParser {
  /** The header, once record 0 has been read. */
  header: LogHeader | null = null;
  /** Index of the next record (the header is 0). */
  recordIndex = 0;
  /** Tick records read so far = the simulation's tick counter after applying them. */
  ticks = 0;
  /** Whether the end record has been read. */
  ended = false;
  private readonly formatVersion: number;

  constructor(formatVersion: number) {
    this.formatVersion = formatVersion;
  }

  /**
   * Reads the record starting at bytes[at] (file offset `fileOffset`), with bytes valid up to `end`.
   * Throws LogCorruptError at this record's index and offset when it is damaged or out of order.
   */
  next(bytes: Uint8Array, at: number, end: number, fileOffset: number): ParseStep {
    const index = this.recordIndex;
    const fail = (reason: string): never => {
      throw new LogCorruptError(index, fileOffset, reason);
    };
    if (this.ended) {
      if (at >= end) return { kind: 'need', totalBytes: 1 };
      fail('data after the end record');
    }
    const scan = scanFrame(bytes, at, end);
    if (scan.kind === 'need') return scan;
    if (scan.kind === 'bad') return fail(scan.reason);
    const ps = scan.payloadStart;
    const pe = scan.payloadEnd;
    const sizeBytes = scan.frameEnd - at;
    const type: RecordTypeCode = scan.type;
    const pos = { index, offset: fileOffset, sizeBytes };
    try {
      if (index === 0) {
        if (type !== RecordType.Header) fail(`the first record is a ${RECORD_TYPE_NAMES[type]} record, not the header`);
        this.header = decodeHeader(bytes.subarray(ps, pe), this.formatVersion);
        this.recordIndex++;
        return { kind: 'header', header: this.header, frameEnd: scan.frameEnd };
      }
      let entry: LogEntry;
      switch (type) {
        case RecordType.Header:
          return fail('a second header record');
        case RecordType.Tick: {
          const record = decodeTick(bytes, ps, pe);
          if (record.tick !== this.ticks) fail(`tick record for tick ${record.tick} out of sequence (expected tick ${this.ticks})`);
          this.ticks++;
          entry = { type: 'tick', ...pos, record };
          break;
        }
        case RecordType.Hash: {
          const h = decodeHash(bytes, ps, pe);
          if (h.tick !== this.ticks) fail(`hash record for tick ${h.tick} out of sequence (tick counter is ${this.ticks})`);
          entry = { type: 'hash', ...pos, tick: h.tick, hash: h.hash };
          break;
        }
        case RecordType.Checkpoint: {
          const c = decodeCheckpoint(bytes, ps, pe);
          if (c.tick !== this.ticks) fail(`checkpoint record for tick ${c.tick} out of sequence (tick counter is ${this.ticks})`);
          entry = { type: 'checkpoint', ...pos, tick: c.tick, bytes: c.bytes };
          break;
        }
        case RecordType.End: {
          const e = decodeEnd(bytes, ps, pe);
          if (e.tick !== this.ticks) fail(`end record says ${e.tick} ticks but ${this.ticks} tick records precede it`);
          this.ended = true;
          entry = { type: 'end', ...pos, tick: e.tick, hash: e.hash };
          break;
        }
        default:
          return fail(`unknown record type ${String(type)}`);
      }
      this.recordIndex++;
      return { kind: 'entry', entry, frameEnd: scan.frameEnd };
    } catch (err) {
      if (err instanceof PayloadError) fail(`malformed ${RECORD_TYPE_NAMES[type]} record: ${err.message}`);
      throw err;
    }
  }
}
