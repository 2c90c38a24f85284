// Streaming input-log reader: an async iterator over a file handle with a bounded window (one chunk, or one record
// when a record is larger), so logs of any length read in constant memory. Reports where corruption starts and
// keeps everything before a truncated tail.
import { open, type FileHandle } from 'node:fs/promises';
import { LogCorruptError, LogFormatError, PRELUDE_BYTES, type LogEntry, type LogHeader, type LogOutcome } from './log-format.ts';
import { checkPrelude, LogParser } from './log-parser.ts';

/** Reader options. */
export interface LogReaderOptions {
  /** Bytes read per file read (default 256 KiB). */
  chunkBytes?: number;
}

/** Reads one log file record by record. Open with LogReader.open(); close() when done. */
export class LogReader {
  /** The file path (for messages). */
  readonly path: string;
  /** The decoded header (validated by open()). */
  header!: LogHeader;
  /** How the read ended; set when entries() finishes or throws. */
  outcome: LogOutcome | null = null;
  private readonly fh: FileHandle;
  private readonly chunkBytes: number;
  private parser!: LogParser;
  private buf: Uint8Array;
  private lo = 0;
  private hi = 0;
  /** File offset of buf[0]. */
  private base = 0;
  private eof = false;
  private started = false;

  private constructor(path: string, fh: FileHandle, chunkBytes: number) {
    this.path = path;
    this.fh = fh;
    this.chunkBytes = chunkBytes;
    this.buf = new Uint8Array(chunkBytes);
  }

  /** Opens a log and validates its prelude and header; throws LogFormatError / LogCorruptError with the path. */
  static async open(path: string, opts: LogReaderOptions = {}): Promise<LogReader> {
    const chunkBytes = opts.chunkBytes ?? 256 * 1024;
    if (!Number.isInteger(chunkBytes) || chunkBytes < 64) throw new Error(`LogReader: chunkBytes must be an integer ≥ 64, got ${chunkBytes}`);
    const fh = await open(path, 'r');
    const reader = new LogReader(path, fh, chunkBytes);
    try {
      await reader.readHeader();
    } catch (err) {
      await fh.close();
      throw err;
    }
    return reader;
  }

  /** Size of the read window in bytes: one chunk, or one whole record when a record is larger (memory bound). */
  get windowBytes(): number {
    return this.buf.length;
  }

  /** Bytes buffered past the read position. */
  private get available(): number {
    return this.hi - this.lo;
  }

  /** Ensures `n` bytes are buffered from the read position, or the file has ended. */
  private async fill(n: number): Promise<void> {
    while (this.available < n && !this.eof) {
      if (this.lo + n > this.buf.length) {
        // Slide the unread bytes to the front; grow to hold one whole record, shrink back after a huge one.
        const size = Math.max(n, this.chunkBytes);
        if (size > this.buf.length || this.buf.length > 4 * this.chunkBytes) {
          const next = new Uint8Array(size);
          next.set(this.buf.subarray(this.lo, this.hi), 0);
          this.buf = next;
        } else {
          this.buf.copyWithin(0, this.lo, this.hi);
        }
        this.base += this.lo;
        this.hi -= this.lo;
        this.lo = 0;
      }
      const { bytesRead } = await this.fh.read(this.buf, this.hi, this.buf.length - this.hi, this.base + this.hi);
      if (bytesRead === 0) this.eof = true;
      this.hi += bytesRead;
    }
  }

  private async readHeader(): Promise<void> {
    await this.fill(PRELUDE_BYTES);
    const version = checkPrelude(this.buf.subarray(this.lo), this.available, this.path);
    this.lo += PRELUDE_BYTES;
    this.parser = new LogParser(version);
    for (;;) {
      let step;
      try {
        step = this.parser.next(this.buf, this.lo, this.hi, this.base + this.lo);
      } catch (err) {
        if (err instanceof LogCorruptError) throw new LogFormatError(`${this.path}: no valid header: ${err.reason}`);
        throw err;
      }
      if (step.kind === 'header') {
        this.header = step.header;
        this.lo = step.frameEnd;
        return;
      }
      if (step.kind === 'need') {
        if (this.eof) throw new LogFormatError(`${this.path} is truncated inside its header record`);
        await this.fill(step.totalBytes);
      }
    }
  }

  private finish(status: LogOutcome['status'], corruption?: LogOutcome['corruption']): LogOutcome {
    const validBytes = this.base + this.lo;
    const outcome: LogOutcome = {
      status,
      records: this.parser.recordIndex,
      ticks: this.parser.ticks,
      validBytes,
      fileBytes: this.base + this.hi,
    };
    if (corruption) outcome.corruption = corruption;
    this.outcome = outcome;
    return outcome;
  }

  /**
   * Yields every record after the header, in file order. Ends normally on a complete, unterminated or truncated
   * log (see `outcome`); throws LogCorruptError after yielding every valid record before a damaged one.
   * Entries are fresh objects (checkpoint bytes are copies): keep them as long as needed.
   */
  async *entries(): AsyncGenerator<LogEntry, LogOutcome, void> {
    if (this.started) throw new Error('LogReader.entries() can be iterated once; open the log again to re-read it');
    this.started = true;
    for (;;) {
      let step;
      try {
        step = this.parser.next(this.buf, this.lo, this.hi, this.base + this.lo);
      } catch (err) {
        if (err instanceof LogCorruptError) {
          const outcome = this.finish('corrupt', { recordIndex: err.recordIndex, byteOffset: err.byteOffset, reason: err.reason });
          outcome.fileBytes = await this.fileSize();
        }
        throw err;
      }
      if (step.kind === 'need') {
        if (this.eof) {
          if (this.available === 0) return this.finish(this.parser.ended ? 'complete' : 'unterminated');
          return this.finish('truncated');
        }
        await this.fill(step.totalBytes);
        continue;
      }
      if (step.kind === 'header') throw new Error('LogReader: unexpected header');
      this.lo = step.frameEnd;
      yield step.entry;
    }
  }

  private async fileSize(): Promise<number> {
    return (await this.fh.stat()).size;
  }

  /** Closes the file. */
  async close(): Promise<void> {
    await this.fh.close();
  }
}
