// Input-log format constants and the decoded record types (see docs/input-log.md for the byte layout).
// Shared by the codec, writer and reader; pure data, no I/O.
import { MAX_PLAYER_ID, MAX_PLAYER_NAME_BYTES } from '../../shared/sim/tick-record.ts';
import type { TickInputRecord } from '../../shared/sim/types.ts';

/** File magic: 0x89 then ASCII "TAOSLOG" (the high byte catches 7-bit transfers and text files). */
export const LOG_MAGIC: Readonly<Uint8Array> = Uint8Array.of(0x89, 0x54, 0x41, 0x4f, 0x53, 0x4c, 0x4f, 0x47);
/** The format version this build writes (it reads this one and every older one in READABLE_LOG_VERSIONS). */
export const LOG_FORMAT_VERSION = 2;
/** Versions this build reads: 1 lacks the scenario module hash (read as ''). */
export const READABLE_LOG_VERSIONS: readonly number[] = [1, 2];
/** Bytes before the first record: magic (8), version u16, flags u16 (must be 0). */
export const PRELUDE_BYTES = 12;

/** Record type bytes. */
export const RecordType = {
  Header: 1,
  Tick: 2,
  Hash: 3,
  Checkpoint: 4,
  End: 5,
} as const;
export type RecordTypeCode = (typeof RecordType)[keyof typeof RecordType];

/** Readable names of the record types, by code. */
export const RECORD_TYPE_NAMES: Readonly<Record<number, string>> = { 1: 'header', 2: 'tick', 3: 'hash', 4: 'checkpoint', 5: 'end' };

/** Largest payload each record type may declare; a larger length is corruption, not a big record. */
export const MAX_PAYLOAD_BYTES: Readonly<Record<number, number>> = {
  [RecordType.Header]: 64 * 1024,
  [RecordType.Tick]: 4 * 1024 * 1024,
  [RecordType.Hash]: 16,
  [RecordType.Checkpoint]: 256 * 1024 * 1024 - 1,
  [RecordType.End]: 32,
};

/** Bytes around a payload: type (1) + length varint (1–4) + header check (1) + CRC-32 (4). */
export const MAX_FRAME_OVERHEAD_BYTES = 10;
/** Longest length varint (4 × 7 bits covers 256 MiB). */
export const MAX_LENGTH_VARINT_BYTES = 4;
/** Longest player name a tick record carries, in UTF-8 bytes (the simulation's own limit). */
export const MAX_NAME_BYTES = MAX_PLAYER_NAME_BYTES;
/** Longest scenario name / parameter name / seed string / createdBy, in UTF-8 bytes. */
export const MAX_HEADER_STRING_BYTES = 1024;
/** Largest player id (unsigned 32-bit, the simulation's own limit). */
export { MAX_PLAYER_ID };

/** The session description at the start of every log. */
export interface LogHeader {
  formatVersion: number;
  /** jolt-physics package version that recorded the log (replays on another version may diverge). */
  joltVersion: string;
  scenario: string;
  /** Content hash of the scenario's module (`sha256:<hex>`), '' for built-in scenarios (and version-1 logs). */
  scenarioHash: string;
  /** Scenario parameters as given (sorted by name when written). */
  params: Record<string, number>;
  seed: number | string;
  tickRateHz: number;
  /** A hash record follows every K-th tick (0: none). */
  hashEveryTicks: number;
  /** A checkpoint record follows every C-th tick (0: none). */
  checkpointEveryTicks: number;
  /** Free text naming the program that wrote the log (e.g. "taos-physics 0.1.0 record"). */
  createdBy: string;
}

/** What every decoded record carries about where it sits in the file. */
export interface RecordPosition {
  /** 0-based record index (the header is record 0). */
  index: number;
  /** Byte offset of the record's type byte in the file. */
  offset: number;
  /** Whole record size in bytes (framing included). */
  sizeBytes: number;
}

/** One decoded record after the header. `tick` on hash/checkpoint/end is the simulation's tick counter then. */
export type LogEntry =
  | (RecordPosition & { type: 'tick'; record: TickInputRecord })
  | (RecordPosition & { type: 'hash'; tick: number; hash: string })
  | (RecordPosition & { type: 'checkpoint'; tick: number; bytes: Uint8Array })
  | (RecordPosition & { type: 'end'; tick: number; hash: string });

/** How a log read ended. */
export type LogStatus = 'complete' | 'unterminated' | 'truncated' | 'corrupt';

/** The outcome of reading a whole log: every entry before `validBytes` was delivered. */
export interface LogOutcome {
  /** complete: end record read; unterminated: clean record boundary but no end record (writer died or is still
   *  running); truncated: a partial record at the tail was dropped; corrupt: see `corruption`. */
  status: LogStatus;
  /** Records delivered, header included. */
  records: number;
  /** Tick records delivered. */
  ticks: number;
  /** Bytes of whole, valid records (prelude included): a safe length to cut the file to. */
  validBytes: number;
  /** Bytes in the file (or buffer) as read. */
  fileBytes: number;
  /** Where the read stopped on a bad record. */
  corruption?: { recordIndex: number; byteOffset: number; reason: string };
}

/** The file is not a readable input log at all: bad magic, unsupported version, or no valid header. */
export class LogFormatError extends Error {
  override name = 'LogFormatError';
}

/** A record failed its checks; everything before `recordIndex` was valid and has been delivered. */
export class LogCorruptError extends Error {
  override name = 'LogCorruptError';
  readonly recordIndex: number;
  readonly byteOffset: number;
  readonly reason: string;

  constructor(recordIndex: number, byteOffset: number, reason: string) {
    super(`input log corrupt at record ${recordIndex} (byte offset ${byteOffset}): ${reason}`);
    this.recordIndex = recordIndex;
    this.byteOffset = byteOffset;
    this.reason = reason;
  }
}
