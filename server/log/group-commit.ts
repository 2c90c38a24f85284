// Group commit for an input log: callers ask to be told once everything appended up to now is on disk; one
// write + fdatasync at a time covers every record appended before it started, and the callers it covers are released
// together, in the order they asked. Owns no file: it drives LogWriter.sync().
import type { LogWriter } from './log-writer.ts';

interface Waiter {
  /** Bytes appended when the caller asked: released once a sync that started at or past it has finished. */
  upToBytes: number;
  fn: () => void;
}

/** Releases callbacks once the log's records before them are durable. */
export class GroupCommit {
  private readonly writer: LogWriter;
  private readonly onError: (error: unknown) => void;
  private waiting: Waiter[] = [];
  private inFlight = false;
  private failed = false;
  /** Syncs issued (each covers every record appended before it). */
  syncs = 0;
  /** Bytes known durable. */
  durableBytes = 0;

  /** `onError` hears the first failed sync; from then on the log is given up and every caller is released at once. */
  constructor(writer: LogWriter, onError: (error: unknown) => void) {
    this.writer = writer;
    this.onError = onError;
    this.durableBytes = writer.bytesAppended;
  }

  /** Calls `fn` once every byte appended so far is durable (at once when it already is). */
  whenDurable(fn: () => void): void {
    if (this.failed) {
      fn();
      return;
    }
    const upToBytes = this.writer.bytesAppended;
    if (upToBytes <= this.durableBytes && this.waiting.length === 0) {
      fn();
      return;
    }
    this.waiting.push({ upToBytes, fn });
    if (!this.inFlight) this.start();
  }

  /** Callers waiting for a sync. */
  get pending(): number {
    return this.waiting.length;
  }

  private start(): void {
    this.inFlight = true;
    const target = this.writer.bytesAppended;
    this.syncs++;
    this.writer.sync().then(
      () => {
        this.inFlight = false;
        this.durableBytes = Math.max(this.durableBytes, target);
        let released = 0;
        while (released < this.waiting.length && this.waiting[released].upToBytes <= this.durableBytes) released++;
        const ready = this.waiting.slice(0, released);
        this.waiting = this.waiting.slice(released);
        for (const w of ready) w.fn();
        if (this.waiting.length > 0) this.start();
      },
      (error: unknown) => {
        this.inFlight = false;
        this.failed = true;
        this.onError(error);
        const all = this.waiting;
        this.waiting = [];
        for (const w of all) w.fn();
      },
    );
  }

  /** Drops every waiting caller (the log is closing; nothing more will be sent). */
  clear(): void {
    this.waiting = [];
  }
}
