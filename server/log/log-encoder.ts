// Turns a session into input-log bytes, record by record, enforcing the same ordering rules the reader checks
// (consecutive ticks, hashes/checkpoints at the current tick, nothing after the end). Pure: no files.
import type { TickInputRecord } from '../../shared/sim/types.ts';
import { ByteWriter } from '../../shared/byte-io.ts';
import { writeFrame } from './frame.ts';
import { LOG_FORMAT_VERSION, LOG_MAGIC, PRELUDE_BYTES, RecordType, type LogHeader } from './log-format.ts';
import { encodeHeader, writeCheckpointHead, writeEndPayload, writeHashPayload, writeTickPayload } from './record-codec.ts';

/** What a writer must say about a session; format version is filled in, a missing scenarioHash is ''. */
export type LogHeaderInit = Omit<LogHeader, 'formatVersion' | 'scenarioHash'> & { scenarioHash?: string };

/**
 * Encodes one log: start() once, then tick/hash/checkpoint records, then end(). Each record can be appended to a
 * caller's ByteWriter (no allocation: the file writer's path) or returned as a fresh array. An invalid call throws
 * and writes nothing.
 */
export class LogEncoder {
  readonly header: LogHeader;
  /** Tick records encoded so far = the simulation's tick counter after them. */
  ticks = 0;
  /** Whether the end record was encoded. */
  ended = false;
  private readonly startBytes: Uint8Array;
  private readonly scratch = new ByteWriter(1024);

  constructor(init: LogHeaderInit) {
    if (init === null || typeof init !== 'object') throw new Error('log header must be an object');
    this.header = { formatVersion: LOG_FORMAT_VERSION, ...init, scenarioHash: init.scenarioHash ?? '', params: { ...init.params } };
    const out = new ByteWriter(256);
    out.raw(LOG_MAGIC);
    out.u16(LOG_FORMAT_VERSION);
    out.u16(0);
    writeFrame(out, RecordType.Header, encodeHeader(this.header));
    if (out.length <= PRELUDE_BYTES) throw new Error('log header: encoding failed');
    this.startBytes = out.finish();
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

  /** Appends the record of one tick's inputs to `out`; its tick must be the next one (0, 1, 2, …). */
  appendTick(out: ByteWriter, record: TickInputRecord): void {
    this.open('tick');
    this.scratch.reset();
    writeTickPayload(this.scratch, record);
    if (record.tick !== this.ticks) throw new Error(`input log: tick record for tick ${record.tick}, expected tick ${this.ticks}`);
    writeFrame(out, RecordType.Tick, this.scratch.view());
    this.ticks++;
  }

  /** Appends a state hash taken when the simulation's tick counter is `tick` (= ticks so far; 0: initial state). */
  appendHash(out: ByteWriter, tick: number, hash: string): void {
    this.open('hash');
    this.scratch.reset();
    writeHashPayload(this.scratch, tick, hash);
    this.atTick(tick, 'hash');
    writeFrame(out, RecordType.Hash, this.scratch.view());
  }

  /** Appends a checkpoint (the simulation's byte form) taken when its tick counter is `tick`. */
  appendCheckpoint(out: ByteWriter, tick: number, bytes: Uint8Array): void {
    this.open('checkpoint');
    this.scratch.reset();
    writeCheckpointHead(this.scratch, tick, bytes);
    this.atTick(tick, 'checkpoint');
    writeFrame(out, RecordType.Checkpoint, this.scratch.view(), bytes);
  }

  /** Appends the end record: final tick counter and state hash. Nothing may follow. */
  appendEnd(out: ByteWriter, tick: number, hash: string): void {
    this.open('end');
    this.scratch.reset();
    writeEndPayload(this.scratch, tick, hash);
    this.atTick(tick, 'end');
    writeFrame(out, RecordType.End, this.scratch.view());
    this.ended = true;
  }

  /** A tick record as a fresh array (see appendTick). */
  tick(record: TickInputRecord): Uint8Array {
    return this.fresh((out) => this.appendTick(out, record));
  }

  /** A hash record as a fresh array (see appendHash). */
  hash(tick: number, hash: string): Uint8Array {
    return this.fresh((out) => this.appendHash(out, tick, hash));
  }

  /** A checkpoint record as a fresh array (see appendCheckpoint). */
  checkpoint(tick: number, bytes: Uint8Array): Uint8Array {
    return this.fresh((out) => this.appendCheckpoint(out, tick, bytes));
  }

  /** The end record as a fresh array (see appendEnd). */
  end(tick: number, hash: string): Uint8Array {
    return this.fresh((out) => this.appendEnd(out, tick, hash));
  }

  private fresh(write: (out: ByteWriter) => void): Uint8Array {
    const out = new ByteWriter(64);
    write(out);
    return out.finish();
  }
}
