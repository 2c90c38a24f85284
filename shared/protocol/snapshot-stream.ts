// Per-client snapshot streams with bounded baseline histories. SnapshotEncoder (server side, one per client) remembers
// the frames it sent, turns acks into the delta baseline and tracks which body descriptors the client already has;
// SnapshotDecoder (client side) keeps the frames it decoded so later deltas find their baselines.
import type { BodyDescriptor } from '../sim/types.ts';
import { SNAPSHOT_HISTORY_SIZE } from './limits.ts';
import { frameIsLive } from './frame-pool.ts';
import type { SnapshotFormat } from './quantization.ts';
import { decodeSnapshot, encodeSnapshot, MAX_BASELINE_AGE, readSnapshotHeader } from './snapshot-codec.ts';
import type { QuantizedFrame } from './snapshot-frame.ts';

/** A bounded map tick → entry that forgets the oldest tick first (so a late, stale entry never pushes out newer ones). */
export class TickHistory<T> {
  readonly capacity: number;
  private readonly entries = new Map<number, T>();
  /** Whether every tick was stored above all before it (then the map's first key is the oldest). */
  private sorted = true;
  private newest = -Infinity;
  /** Told of every entry the history lets go of (replaced, evicted or cleared). */
  private readonly onDrop: ((entry: T) => void) | undefined;

  constructor(capacity: number, onDrop?: (entry: T) => void) {
    if (!Number.isInteger(capacity) || capacity < 1) throw new Error(`TickHistory: capacity must be a positive integer, got ${capacity}`);
    this.capacity = capacity;
    this.onDrop = onDrop;
  }

  /** Stores an entry (replacing one with the same tick) and evicts the oldest ticks beyond capacity. */
  set(tick: number, entry: T): void {
    // Ticks stored in rising order keep the map's insertion order sorted: its first key is then the oldest.
    const replaced = this.entries.get(tick);
    if (replaced === undefined && tick < this.newest) this.sorted = false;
    this.newest = Math.max(this.newest, tick);
    this.entries.set(tick, entry);
    if (replaced !== undefined && replaced !== entry) this.onDrop?.(replaced);
    while (this.entries.size > this.capacity) {
      let oldest = Infinity;
      if (this.sorted) oldest = this.entries.keys().next().value!;
      else for (const t of this.entries.keys()) if (t < oldest) oldest = t;
      const dropped = this.entries.get(oldest)!;
      this.entries.delete(oldest);
      this.onDrop?.(dropped);
    }
  }

  /** The entry for a tick, if still held. */
  get(tick: number): T | undefined {
    return this.entries.get(tick);
  }

  /** Entries held. */
  get size(): number {
    return this.entries.size;
  }

  /** Forgets everything. */
  clear(): void {
    if (this.onDrop !== undefined) for (const entry of this.entries.values()) this.onDrop(entry);
    this.entries.clear();
    this.sorted = true;
    this.newest = -Infinity;
  }
}

/** Ids of the ascending list `before` that are missing from the ascending list `after` (bodies removed). */
function removedIds(before: Uint32Array, after: Uint32Array): number[] {
  const out: number[] = [];
  let j = 0;
  for (let i = 0; i < before.length; i++) {
    const id = before[i];
    while (j < after.length && after[j] < id) j++;
    if (j >= after.length || after[j] !== id) out.push(id);
  }
  return out;
}

/** Ids of the ascending list `after` that are missing from the ascending list `before` (bodies new since then). */
function addedIds(before: Uint32Array, after: Uint32Array): number[] {
  return removedIds(after, before);
}

const NO_DESCRIPTORS = Object.freeze([]) as unknown as BodyDescriptor[];
const NO_IDS: ArrayLike<number> = Object.freeze([]);

/** A spawned body's descriptor; a body without one is a server bug, not a client's doing. */
function describeOne(id: number, describe: (bodyId: number) => BodyDescriptor | undefined): BodyDescriptor {
  const d = describe(id);
  if (d === undefined) throw new Error(`SnapshotEncoder: no descriptor for spawned body ${id}`);
  return d;
}

function describeAll(ids: ArrayLike<number>, describe: (bodyId: number) => BodyDescriptor | undefined): BodyDescriptor[] {
  const out: BodyDescriptor[] = [];
  for (let i = 0; i < ids.length; i++) out.push(describeOne(ids[i], describe));
  return out;
}

/**
 * Work on one frame shared by the encoders of a room (same frame object, same format): encoded bytes, the ids new
 * since a baseline and the descriptors of all of them (for clients that hold none yet), each by baseline tick (-1:
 * full snapshot), and the ids removed since a previous frame's id list.
 */
export class SharedFrameWork {
  readonly bytes = new Map<number, Uint8Array>();
  readonly fresh = new Map<number, ArrayLike<number>>();
  readonly freshDescriptors = new Map<number, BodyDescriptor[]>();
  readonly removed = new Map<Uint32Array, number[]>();
}

/** One encoded snapshot for one client. */
export interface EncodedSnapshot {
  tick: number;
  /** The encoded frame (docs/protocol.md, "Snapshots", "Layout"). */
  bytes: Uint8Array;
  /** The acked frame this is a delta against; null for a full snapshot. */
  baselineTick: number | null;
  /**
   * Descriptors of bodies in this snapshot the client is not known to have (spawns since its baseline). Read only:
   * clients of a room on the same baseline may get the same (frozen when empty) array.
   */
  descriptors: BodyDescriptor[];
  /**
   * Whether `descriptors` are those of every body new since the baseline (the client held none of them): then they
   * are the same for every client of the room on that baseline, and so is the message that carries them.
   */
  allFresh: boolean;
}

/** What an ack did. */
export type AckOutcome = 'baseline' | 'older' | 'unknown';

interface SentSnapshot {
  frame: QuantizedFrame;
  descriptorIds: ArrayLike<number>;
}

/** Encoder statistics (for metrics). */
export interface SnapshotEncoderStats {
  full: number;
  delta: number;
  bytes: number;
  acks: number;
  unknownAcks: number;
}

/**
 * The server's per-client snapshot state. Baseline rule: the newest acked frame still in the history (the last
 * `historySize` snapshots sent to this client); with none, a full snapshot. A descriptor counts as delivered once a
 * snapshot that carried it is acked (or after markDescriptorsKnown, for the welcome's bodies).
 */
export class SnapshotEncoder {
  readonly format: SnapshotFormat;
  private readonly sent: TickHistory<SentSnapshot>;
  private ackedTick = -1;
  private readonly known = new Set<number>();
  /** The frame of the previous encode (retained: its body ids tell which bodies are gone by the next one). */
  private previous: QuantizedFrame | null = null;
  private readonly counters: SnapshotEncoderStats = { full: 0, delta: 0, bytes: 0, acks: 0, unknownAcks: 0 };

  private lastFullTick = -1;
  private readonly fullRetryTicks: number;

  /**
   * historySize: sent snapshots kept as possible baselines (default SNAPSHOT_HISTORY_SIZE).
   * fullRetryTicks: how long shouldSend() holds back after a full snapshot that is not acked yet (default 30).
   */
  constructor(format: SnapshotFormat, opts: { historySize?: number; fullRetryTicks?: number } = {}) {
    this.format = format;
    // A pooled frame stays retained while it can be a baseline (frame-pool.ts).
    this.sent = new TickHistory<SentSnapshot>(opts.historySize ?? SNAPSHOT_HISTORY_SIZE, (entry) => entry.frame.lease?.release());
    this.fullRetryTicks = opts.fullRetryTicks ?? 30;
    if (!Number.isInteger(this.fullRetryTicks) || this.fullRetryTicks < 0) throw new Error(`SnapshotEncoder: fullRetryTicks must be an integer ≥ 0, got ${opts.fullRetryTicks}`);
  }

  /**
   * Whether a snapshot is worth sending at this tick: false while the client has no baseline and a full snapshot
   * went out less than fullRetryTicks ago (another full one would only repeat it; the ack is on its way).
   */
  shouldSend(tick: number): boolean {
    if (this.baselineTick !== null || this.lastFullTick < 0) return true;
    return tick - this.lastFullTick >= this.fullRetryTicks || tick < this.lastFullTick;
  }

  /** Records descriptors delivered reliably outside snapshots (the welcome's dynamic bodies). */
  markDescriptorsKnown(bodyIds: Iterable<number>): void {
    for (const id of bodyIds) this.known.add(id);
  }

  /** Whether the client is known to hold a body's descriptor. */
  knowsDescriptor(bodyId: number): boolean {
    return this.known.has(bodyId);
  }

  /** Applies a client's ack; acks of unsent or evicted ticks are ignored ('unknown'), older acks never move back. */
  acknowledge(tick: number): AckOutcome {
    const entry = this.sent.get(tick);
    if (entry === undefined) {
      this.counters.unknownAcks++;
      return 'unknown';
    }
    this.counters.acks++;
    const ids = entry.descriptorIds;
    for (let i = 0; i < ids.length; i++) this.known.add(ids[i]);
    if (tick > this.ackedTick) {
      this.ackedTick = tick;
      return 'baseline';
    }
    return 'older';
  }

  /** The tick the next delta will be based on, or null when the next snapshot will be full. */
  get baselineTick(): number | null {
    return this.ackedTick >= 0 && this.sent.get(this.ackedTick) !== undefined ? this.ackedTick : null;
  }

  /** Counters since creation. */
  get stats(): Readonly<SnapshotEncoderStats> {
    return this.counters;
  }

  /**
   * Encodes a frame for this client and remembers it as a possible baseline. `describe(id)` returns a body's
   * descriptor; a spawned body without one throws (a server bug, not a client's doing). `shared` (optional) is the
   * work cache of THIS frame object and the same format, used by every client of a room in one tick: the encoded
   * bytes and the scan for bodies new since a baseline then cost once per distinct baseline instead of once per client.
   */
  encode(frame: QuantizedFrame, describe: (bodyId: number) => BodyDescriptor | undefined, shared?: SharedFrameWork): EncodedSnapshot {
    const baseEntry = this.ackedTick >= 0 ? this.sent.get(this.ackedTick) : undefined;
    // A pooled baseline is retained while in the history; frameIsLive guards against a holder that let go too early.
    const usable = baseEntry !== undefined && baseEntry.frame.tick < frame.tick && frame.tick - baseEntry.frame.tick <= MAX_BASELINE_AGE && frameIsLive(baseEntry.frame);
    const baseline = usable ? baseEntry.frame : null;
    // The bytes depend only on (format, frame, baseline): clients of one room that acked the same tick share them.
    const key = baseline === null ? -1 : baseline.tick;
    let bytes = shared?.bytes.get(key);
    if (bytes === undefined) {
      bytes = encodeSnapshot(this.format, frame, baseline);
      shared?.bytes.set(key, bytes);
    }
    // Bodies gone since the previous encode are forgotten, so a reused id gets its new descriptor.
    const previous = this.previous;
    if (previous !== null && previous !== frame && this.known.size > 0) {
      if (!frameIsLive(previous)) this.known.clear(); // which bodies left is lost: resend descriptors rather than miss one
      else {
        let gone = shared?.removed.get(previous.bodyIds);
        if (gone === undefined) {
          gone = removedIds(previous.bodyIds, frame.bodyIds);
          shared?.removed.set(previous.bodyIds, gone);
        }
        for (const id of gone) this.known.delete(id);
      }
    }
    if (previous !== frame) {
      frame.lease?.retain();
      previous?.lease?.release();
      this.previous = frame;
    }
    // Candidates for descriptors: bodies of the frame missing from the baseline (all of them for a full snapshot).
    let fresh = shared?.fresh.get(key);
    if (fresh === undefined) {
      fresh = baseline === null ? frame.bodyIds : addedIds(baseline.bodyIds, frame.bodyIds);
      shared?.fresh.set(key, fresh);
    }
    let unknown = 0;
    for (let i = 0; i < fresh.length; i++) if (!this.known.has(fresh[i])) unknown++;
    let descriptors = NO_DESCRIPTORS;
    let descriptorIds: ArrayLike<number> = NO_IDS;
    const allFresh = unknown === fresh.length;
    if (allFresh && unknown > 0) {
      // The common case of a room in step: every client on this baseline lacks the same bodies; described once.
      descriptors = shared?.freshDescriptors.get(key) ?? describeAll(fresh, describe);
      shared?.freshDescriptors.set(key, descriptors);
      descriptorIds = fresh;
    } else if (unknown > 0) {
      const own: BodyDescriptor[] = [];
      const ownIds: number[] = [];
      for (let i = 0; i < fresh.length; i++) {
        const id = fresh[i];
        if (this.known.has(id)) continue;
        own.push(describeOne(id, describe));
        ownIds.push(id);
      }
      descriptors = own;
      descriptorIds = ownIds;
    }
    frame.lease?.retain();
    this.sent.set(frame.tick, { frame, descriptorIds });
    if (baseline === null) {
      this.counters.full++;
      this.lastFullTick = frame.tick;
    }
    else this.counters.delta++;
    this.counters.bytes += bytes.length;
    return { tick: frame.tick, bytes, baselineTick: baseline === null ? null : baseline.tick, descriptors, allFresh };
  }

  /** Forgets every sent frame and ack (the next snapshot is full); known descriptors stay known. */
  reset(): void {
    this.sent.clear();
    this.ackedTick = -1;
    this.lastFullTick = -1;
  }
}

/** One decoded snapshot. */
export interface DecodedSnapshot {
  frame: QuantizedFrame;
  baselineTick: number | null;
  sizeBytes: number;
}

/**
 * The client's side: decodes snapshots against frames it decoded before and keeps the last `historySize` of them.
 * Ack a snapshot only after decode() returned it.
 */
export class SnapshotDecoder {
  readonly format: SnapshotFormat;
  private readonly frames: TickHistory<QuantizedFrame>;
  private newest: QuantizedFrame | null = null;

  constructor(format: SnapshotFormat, opts: { historySize?: number } = {}) {
    this.format = format;
    this.frames = new TickHistory(opts.historySize ?? SNAPSHOT_HISTORY_SIZE);
  }

  /** Decodes bytes into the server's exact frame; throws a clear Error on a missing baseline or corrupt bytes. */
  decode(bytes: Uint8Array): DecodedSnapshot {
    const reference = this.newest?.tick ?? null;
    const frame = decodeSnapshot(this.format, bytes, (tick) => this.frames.get(tick), reference);
    this.frames.set(frame.tick, frame);
    if (this.newest === null || frame.tick > this.newest.tick) this.newest = frame;
    const header = readSnapshotHeader(bytes, reference);
    return { frame, baselineTick: header.baselineTick, sizeBytes: bytes.length };
  }

  /** The decoded frame for a tick, if held. */
  frame(tick: number): QuantizedFrame | undefined {
    return this.frames.get(tick);
  }

  /** The newest decoded frame. */
  latest(): QuantizedFrame | null {
    return this.newest;
  }
}
