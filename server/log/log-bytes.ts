// In-memory input-log reader: the same rules as the streaming reader, for a log already held as bytes (tests,
// small logs, logs received over the wire). Never throws on damage past the header: the outcome says where.
import { LogCorruptError, LogFormatError, PRELUDE_BYTES, type LogEntry, type LogHeader, type LogOutcome } from './log-format.ts';
import { checkPrelude, LogParser } from './log-parser.ts';

/** A whole log read from bytes: the header, every valid entry, and how the read ended. */
export interface LogContents {
  header: LogHeader;
  entries: LogEntry[];
  outcome: LogOutcome;
}

/** Reads a log held in memory. Throws LogFormatError if the prelude or header is unusable. */
export function readLogBytes(bytes: Uint8Array, source = 'input log'): LogContents {
  const version = checkPrelude(bytes, bytes.length, source);
  const parser = new LogParser(version);
  const entries: LogEntry[] = [];
  let header: LogHeader | null = null;
  let at = PRELUDE_BYTES;
  const outcome = (status: LogOutcome['status'], corruption?: LogOutcome['corruption']): LogOutcome => {
    const o: LogOutcome = { status, records: parser.recordIndex, ticks: parser.ticks, validBytes: at, fileBytes: bytes.length };
    if (corruption) o.corruption = corruption;
    return o;
  };
  for (;;) {
    let step;
    try {
      step = parser.next(bytes, at, bytes.length, at);
    } catch (err) {
      if (!(err instanceof LogCorruptError)) throw err;
      if (header === null) throw new LogFormatError(`${source}: no valid header: ${err.reason}`);
      return { header, entries, outcome: outcome('corrupt', { recordIndex: err.recordIndex, byteOffset: err.byteOffset, reason: err.reason }) };
    }
    if (step.kind === 'need') {
      if (header === null) throw new LogFormatError(`${source} is truncated inside its header record`);
      const status = at === bytes.length ? (parser.ended ? 'complete' : 'unterminated') : 'truncated';
      return { header, entries, outcome: outcome(status) };
    }
    if (step.kind === 'header') header = step.header;
    else entries.push(step.entry);
    at = step.frameEnd;
  }
}
