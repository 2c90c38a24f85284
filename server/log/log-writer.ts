// Append-only input-log file writer with a documented durability policy: records are buffered in memory, handed
// to the OS every `flushEveryTicks` tick records (and at 1 MiB), and fsynced at every checkpoint and on close.
// Records are written whole and in order, and bytes already written are never rewritten.
import { open, type FileHandle } from 'node:fs/promises';
import { dirname } from 'node:path';
import type { TickInputRecord } from '../../shared/sim/types.ts';
import { ByteWriter } from '../../shared/byte-io.ts';
import { LogEncoder, type LogHeaderInit } from './log-encoder.ts';
import type { LogHeader } from './log-format.ts';

/** Writer options (see docs/input-log.md, "Durability"). */
export interface LogWriterOptions {
  /** Hand buffered records to the OS after this many tick records (default DEFAULT_FLUSH_EVERY_TICKS). */
  flushEveryTicks?: number;
  /** Also flush once this many bytes are buffered (default 1 MiB). */
  flushAtBytes?: number;
  /** fsync after each checkpoint record (default true). */
  syncOnCheckpoint?: boolean;
  /** Replace an existing file (default false: an existing file is an error, never clobbered). */
  overwrite?: boolean;
}

/** Initial size of the pending buffer; it grows as needed and is replaced after holding something huge. */
const PENDING_BYTES = 64 * 1024;
/** How many tick records a writer buffers before handing them to the OS by default: one second of play. */
export const DEFAULT_FLUSH_EVERY_TICKS = 60;

/** Writes one session's input log. Create with LogWriter.create(); always close() (or abandon()) it. */
export class LogWriter {
  readonly path: string;
  private readonly fh: FileHandle;
  private readonly encoder: LogEncoder;
  private readonly flushEveryTicks: number;
  private readonly flushAtBytes: number;
  private readonly syncOnCheckpoint: boolean;
  private pending = new ByteWriter(PENDING_BYTES);
  private ticksSinceFlush = 0;
  private chain: Promise<void> = Promise.resolve();
  private failure: Error | null = null;
  private closed = false;
  /** Bytes appended (buffered or written). */
  bytesAppended = 0;
  /** Bytes the OS has accepted. */
  bytesWritten = 0;

  private constructor(path: string, fh: FileHandle, encoder: LogEncoder, opts: LogWriterOptions) {
    this.path = path;
    this.fh = fh;
    this.encoder = encoder;
    this.flushEveryTicks = opts.flushEveryTicks ?? DEFAULT_FLUSH_EVERY_TICKS;
    this.flushAtBytes = opts.flushAtBytes ?? 1024 * 1024;
    this.syncOnCheckpoint = opts.syncOnCheckpoint ?? true;
  }

  /**
   * Creates the file, writes and fsyncs the prelude and header (and the directory entry), and returns the writer.
   * Throws a clear Error on a bad header or option, or if the file exists and `overwrite` is not set.
   */
  static async create(path: string, header: LogHeaderInit, opts: LogWriterOptions = {}): Promise<LogWriter> {
    for (const key of ['flushEveryTicks', 'flushAtBytes'] as const) {
      const v = opts[key];
      if (v !== undefined && (!Number.isInteger(v) || v < 1)) throw new Error(`LogWriter: ${key} must be a positive integer, got ${String(v)}`);
    }
    const encoder = new LogEncoder(header);
    let fh: FileHandle;
    try {
      fh = await open(path, opts.overwrite ? 'w' : 'wx');
    } catch (err) {
      const e = err as NodeJS.ErrnoException;
      if (e.code === 'EEXIST') throw new Error(`${path} already exists (refusing to overwrite an input log; remove it or pass overwrite)`);
      throw new Error(`cannot create input log ${path}: ${e.message}`);
    }
    const writer = new LogWriter(path, fh, encoder, opts);
    writer.pending.raw(encoder.start());
    writer.bytesAppended = writer.pending.length;
    try {
      await writer.flushNow(true);
      await syncDirectory(dirname(path));
    } catch (err) {
      await fh.close().catch(() => undefined);
      throw err;
    }
    return writer;
  }

  /**
   * Reopens an unterminated log to go on appending after its last whole record: the file is cut to `validBytes`
   * (dropping a partial or damaged tail the caller has set aside) and the next tick record must be `ticks`.
   */
  static async continue(path: string, header: LogHeaderInit, at: { ticks: number; validBytes: number }, opts: LogWriterOptions = {}): Promise<LogWriter> {
    const encoder = new LogEncoder(header);
    encoder.ticks = at.ticks;
    let fh: FileHandle;
    try {
      fh = await open(path, 'a');
    } catch (err) {
      throw new Error(`cannot reopen input log ${path}: ${(err as Error).message}`);
    }
    const writer = new LogWriter(path, fh, encoder, opts);
    try {
      const { size } = await fh.stat();
      if (size < at.validBytes) throw new Error(`input log ${path} has ${size} bytes, fewer than the ${at.validBytes} it was read with`);
      if (size > at.validBytes) await fh.truncate(at.validBytes);
      await fh.datasync();
    } catch (err) {
      await fh.close().catch(() => undefined);
      throw err;
    }
    writer.bytesAppended = at.validBytes;
    writer.bytesWritten = at.validBytes;
    return writer;
  }

  /** The header as written. */
  get header(): LogHeader {
    return this.encoder.header;
  }

  /** Tick records appended so far. */
  get ticks(): number {
    return this.encoder.ticks;
  }

  private usable(): void {
    if (this.failure) throw this.failure;
    if (this.closed) throw new Error(`input log ${this.path} is closed`);
  }

  /** Runs an encoder call that appends to the pending buffer and counts what it added. */
  private append(write: (out: ByteWriter) => void): void {
    const before = this.pending.length;
    write(this.pending);
    this.bytesAppended += this.pending.length - before;
  }

  /** Queues the buffered bytes (then an fsync if asked) behind earlier writes; resolves when done. */
  private flushNow(sync: boolean): Promise<void> {
    const size = this.pending.length;
    const data = size > 0 ? this.pending.finish() : null;
    if (this.pending.capacityBytes > 16 * PENDING_BYTES) this.pending = new ByteWriter(PENDING_BYTES);
    else this.pending.reset();
    this.ticksSinceFlush = 0;
    const job = this.chain.then(async () => {
      if (this.failure) throw this.failure;
      if (data) {
        for (let off = 0; off < size; ) {
          const { bytesWritten } = await this.fh.write(data, off, size - off);
          off += bytesWritten;
          this.bytesWritten += bytesWritten;
        }
      }
      if (sync) await this.fh.datasync();
    });
    this.chain = job.catch((err: unknown) => {
      this.failure ??= new Error(`input log write to ${this.path} failed: ${(err as Error).message}`);
    });
    return job.catch((err: unknown) => {
      throw this.failure ?? err;
    });
  }

  private background(sync: boolean): void {
    this.flushNow(sync).catch(() => undefined); // the failure is kept and thrown by the next call
  }

  /** Appends one tick's input record (write-ahead: before the simulation applies it). */
  appendTick(record: TickInputRecord): void {
    this.usable();
    this.append((out) => this.encoder.appendTick(out, record));
    this.ticksSinceFlush++;
    if (this.ticksSinceFlush >= this.flushEveryTicks || this.pending.length >= this.flushAtBytes) this.background(false);
  }

  /** Appends a state hash taken at tick counter `tick`. */
  appendHash(tick: number, hash: string): void {
    this.usable();
    this.append((out) => this.encoder.appendHash(out, tick, hash));
  }

  /** Appends a checkpoint taken at tick counter `tick`, then flushes (and fsyncs, per options) in the background. */
  appendCheckpoint(tick: number, bytes: Uint8Array): void {
    this.usable();
    this.append((out) => this.encoder.appendCheckpoint(out, tick, bytes));
    this.background(this.syncOnCheckpoint);
  }

  /** Resolves once every write queued so far (automatic flushes included) has finished; never rejects. */
  settled(): Promise<void> {
    return this.chain;
  }

  /** Hands every buffered record to the OS. */
  async flush(): Promise<void> {
    this.usable();
    await this.flushNow(false);
  }

  /** Flushes and fsyncs: everything appended so far survives a power loss. */
  async sync(): Promise<void> {
    this.usable();
    await this.flushNow(true);
  }

  /** Appends the end record (final tick counter and hash), flushes, fsyncs and closes the file. */
  async close(finalTick: number, finalHash: string): Promise<void> {
    if (this.failure && !this.closed) {
      this.closed = true;
      await this.fh.close().catch(() => undefined);
      throw this.failure;
    }
    this.usable();
    this.append((out) => this.encoder.appendEnd(out, finalTick, finalHash));
    this.closed = true;
    try {
      await this.flushNow(true);
    } finally {
      await this.fh.close();
    }
  }

  /** Flushes what was appended and closes the file without an end record (the log reads as unterminated). */
  async abandon(): Promise<void> {
    if (this.closed) return;
    this.closed = true;
    try {
      await this.flushNow(false);
    } finally {
      await this.fh.close();
    }
  }
}

/** fsyncs a directory so a newly created file's name is durable (best effort: not every platform allows it). */
async function syncDirectory(dir: string): Promise<void> {
  let dh: FileHandle | null = null;
  try {
    dh = await open(dir, 'r');
    await dh.sync();
  } catch {
    // Directories cannot be opened or fsynced on some platforms (Windows); the file itself is synced.
  } finally {
    await dh?.close().catch(() => undefined);
  }
}
