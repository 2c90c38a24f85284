// Turns a session into input-log bytes, record by record, enforcing the same ordering rules the reader checks
// (consecutive ticks, hashes/checkpoints at the current tick, nothing after the end). Pure: no files.
import type { TickInputRecord } from '../../shared/sim/types.ts';
import { encodeFrame } from './frame.ts';
import { LOG_FORMAT_VERSION, LOG_MAGIC, PRELUDE_BYTES, RecordType, type LogHeader } from './log-format.ts';
import { encodeCheckpoint, encodeEnd, encodeHash, encodeHeader, encodeTick } from './record-codec.ts';

/** What a writer must say about a session; format version is filled in. */
export type LogHeaderInit = Omit<LogHeader, 'formatVersion'>;

/** Encodes one log: start() once, then tick/hash/checkpoint records, then end(). Invalid calls throw, changing nothing. */
export class LogEncoder {
  readonly header: LogHeader;
  /** Tick records encoded so far = the simulation's tick counter after them. */
  ticks = 0;
  /** Whether end() was called. */
  ended = false;
  private readonly startBytes: Uint8Array;

  constructor(init: LogHeaderInit) {
    this.header = { formatVersion: LOG_FORMAT_VERSION, ...init, params: { ...init.params } };
    const frame = encodeFrame(RecordType.Header, encodeHeader(this.header));
    const out = new Uint8Array(PRELUDE_BYTES + frame.length);
    out.set(LOG_MAGIC, 0);
    out[8] = LOG_FORMAT_VERSION & 0xff;
    out[9] = LOG_FORMAT_VERSION >> 8;
    out.set(frame, PRELUDE_BYTES);
    this.startBytes = out;
  }

  /** The prelude and header record: the first bytes of the file. */
  start(): Uint8Array {
    return this.startBytes;
  }

  private open(what: string): void {
    if (this.ended) throw new Error(`input log: cannot add a ${what} record after the end record`);
  }

  private atTick(tick: number, what: string): void {
    if (tick !== this.ticks) throw new Error(`input log: ${what} record for tick ${tick}, but the log is at tick ${this.ticks} (${this.ticks} tick records written)`);
  }

  /** The record of one tick's inputs; its tick must be the next one (0, 1, 2, …). */
  tick(record: TickInputRecord): Uint8Array {
    this.open('tick');
    const frame = encodeFrame(RecordType.Tick, encodeTick(record));
    if (record.tick !== this.ticks) throw new Error(`input log: tick record for tick ${record.tick}, expected tick ${this.ticks}`);
    this.ticks++;
    return frame;
  }

  /** A state hash taken when the simulation's tick counter is `tick` (= ticks written so far; 0: initial state). */
  hash(tick: number, hash: string): Uint8Array {
    this.open('hash');
    const frame = encodeFrame(RecordType.Hash, encodeHash(tick, hash));
    this.atTick(tick, 'hash');
    return frame;
  }

  /** A checkpoint (the simulation's byte form) taken when its tick counter is `tick`. */
  checkpoint(tick: number, bytes: Uint8Array): Uint8Array {
    this.open('checkpoint');
    const frame = encodeFrame(RecordType.Checkpoint, encodeCheckpoint(tick, bytes));
    this.atTick(tick, 'checkpoint');
    return frame;
  }

  /** The end record: final tick counter and state hash. Nothing may follow. */
  end(tick: number, hash: string): Uint8Array {
    this.open('end');
    const frame = encodeFrame(RecordType.End, encodeEnd(tick, hash));
    this.atTick(tick, 'end');
    this.ended = true;
    return frame;
  }
}
