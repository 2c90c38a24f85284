// A room's snapshot and event fan-out: the work every member shares, done once per tick. One snapshot format per
// room, each world frame quantized once (bodies whose pose has not changed keep the previous frame's integers) into
// pooled arrays, its bit-packing shared by every member's encoder, and each framed message built once for all members.
import {
  createSnapshotFormat,
  encodeServerMessage,
  quantizeFrame,
  QuantizedFramePool,
  SharedFrameWork,
  type EncodedSnapshot,
  type QuantizedFrame,
  type SnapshotEncoder,
  type SnapshotFormat,
} from '../shared/protocol/index.ts';
import type { Vec3Like } from '../shared/physics/index.ts';
import type { GameStateValue } from '../shared/sim/game-state.ts';
import type { BodyDescriptor, SimEvent } from '../shared/sim/types.ts';
import type { WorldFrame } from './room.ts';

/**
 * A message many members get, as a Buffer over the same bytes: the socket layer (ws) takes a Buffer as it is, where it
 * would wrap a plain Uint8Array in a new Buffer for every member it is sent to.
 */
function sharedBytes(bytes: Uint8Array): Uint8Array {
  return Buffer.from(bytes.buffer, bytes.byteOffset, bytes.byteLength);
}

/** What the fan-out needs to know of its room. */
export interface FanOutSource {
  /** Where the room's bodies live: the snapshot position grid. */
  readonly bounds: { min: Vec3Like; max: Vec3Like };
  /** Whether a body is part of the scene's built static geometry (sent in the welcome, never in snapshots). */
  isSceneStatic(bodyId: number): boolean;
  /** A live body's descriptor (spawned bodies travel with the first snapshot that carries them). */
  describe(bodyId: number): BodyDescriptor | undefined;
  /** The room's game state version now (changes whenever the state does); null when the scenario declares none. */
  gameStateVersion?(): number | null;
  /** The game state values in field order. */
  gameStateValues?(): GameStateValue[];
}

/** The work one world frame shares between members. */
interface FrameWork {
  readonly frame: WorldFrame;
  readonly quantized: QuantizedFrame;
  readonly shared: SharedFrameWork;
  /** The room's game state version at this frame (null: the scenario declares none): read once, not per member. */
  readonly stateVersion: number | null;
  /** Framed snapshot messages without descriptors, by baseline tick (−1: full) and whether the state rides along. */
  readonly plain: Map<number, Uint8Array>;
  /** Framed snapshot messages by baseline tick and the descriptors they carry. */
  readonly messages: Map<string, Uint8Array>;
}

/** One member's snapshot of a frame: the framed message and what the encoder made of it. */
export interface MemberSnapshot {
  message: Uint8Array;
  encoded: EncodedSnapshot;
  /** The game state version this member now holds (pass it to the next snapshotFor); −1 when there is no game state. */
  stateVersion: number;
}

/** A room's shared per-tick snapshot and event work; the room owns one. */
export class SnapshotFanOut {
  private readonly source: FanOutSource;
  private formatCache: SnapshotFormat | null = null;
  private work: FrameWork | null = null;
  /** The latest quantized frame (retained) and the body copies it came from (the next frame's starting point). */
  private last: { bodies: WorldFrame['bodies']; frame: QuantizedFrame } | null = null;
  /**
   * Buffers of quantized frames: a frame's goes back once the fan-out and every encoder history let go of it, so a
   * snapshot tick reuses one instead of allocating ~37 KB for 1000 bodies (tens of µs, sometimes more, after a step).
   */
  private readonly pool = new QuantizedFramePool();
  private events: { list: readonly SimEvent[]; message: Uint8Array } | null = null;
  private state: { version: number; values: GameStateValue[] } | null = null;
  /** Body copies of a frame that was quantized and then followed by a newer one: free for the next frame's copy. */
  private spare: WorldFrame['bodies'] | null = null;

  constructor(source: FanOutSource) {
    this.source = source;
  }

  /** The room's snapshot format (every member's encoder uses it); made on first use. */
  get format(): SnapshotFormat {
    this.formatCache ??= createSnapshotFormat(this.source.bounds);
    return this.formatCache;
  }

  /** Quantized-frame buffers handed out so far, and how many of them were reused (for tests and figures). */
  get framePoolCounts(): Readonly<{ taken: number; reused: number }> {
    return this.pool.counts;
  }

  /**
   * Body arrays of an earlier frame that nothing reads any more (its quantized form replaced it), handed out once:
   * captureFrame copies the next frame into them instead of allocating. Null when there are none.
   */
  takeSpareBodies(): WorldFrame['bodies'] | null {
    const spare = this.spare;
    this.spare = null;
    return spare;
  }

  /** The framed events message of a tick: the room hands every member the same list, framed once. */
  eventsMessage(events: readonly SimEvent[]): Uint8Array {
    if (this.events?.list !== events) this.events = { list: events, message: sharedBytes(encodeServerMessage({ type: 'events', events: [...events] })) };
    return this.events.message;
  }

  /**
   * A member's snapshot of `frame` from its encoder. Members that share a baseline and the spawned bodies they still
   * lack get the very same message (a descriptor is the same object for every member within a tick).
   */
  snapshotFor(encoder: SnapshotEncoder, frame: WorldFrame, heldStateVersion = -1): MemberSnapshot {
    const work = this.frameWork(frame);
    const encoded = encoder.encode(work.quantized, (id) => work.frame.descriptors?.get(id) ?? this.source.describe(id), work.shared);
    // The whole game state rides along when it changed since the member's last snapshot (the link is ordered and
    // reliable, so what a member got last is what it holds).
    const stateVersion = work.stateVersion;
    const withState = stateVersion !== null && stateVersion !== heldStateVersion;
    // Most members share a baseline and lack either no descriptor or every new body's (the room in step): a number
    // keys their message, no string is built.
    const plainKey = encoded.allFresh || encoded.descriptors.length === 0 ? (encoded.baselineTick ?? -1) * 4 + (encoded.descriptors.length > 0 ? 2 : 0) + (withState ? 1 : 0) : null;
    let key = '';
    if (plainKey === null) {
      key = `${encoded.baselineTick ?? -1}${withState ? 's' : ''}`;
      for (const d of encoded.descriptors) key += `,${d.id}`;
    }
    let message = plainKey === null ? work.messages.get(key) : work.plain.get(plainKey);
    if (!message) {
      const state = withState ? this.stateValues(stateVersion) : undefined;
      message = sharedBytes(encodeServerMessage({ type: 'snapshot', bytes: encoded.bytes, descriptors: encoded.descriptors, ...(state ? { state } : {}) }));
      if (plainKey === null) work.messages.set(key, message);
      else work.plain.set(plainKey, message);
    }
    return { message, encoded, stateVersion: stateVersion ?? -1 };
  }

  private stateValues(version: number): GameStateValue[] {
    if (this.state?.version !== version) this.state = { version, values: this.source.gameStateValues?.() ?? [] };
    return this.state.values;
  }

  private frameWork(frame: WorldFrame): FrameWork {
    if (this.work?.frame === frame) return this.work;
    const last = this.last;
    const previous = last !== null && last.frame.tick < frame.tick ? { read: last.bodies, frame: last.frame } : undefined;
    const quantized = quantizeFrame(this.format, frame.tick, frame.bodies, frame.characters, { includeStatic: (id) => !this.source.isSceneStatic(id), previous, pool: this.pool });
    quantized.lease?.retain();
    // The previous frame's body copies are read by nothing once this frame is quantized: the room copies into them next.
    if (last !== null && last.bodies !== frame.bodies) this.spare = last.bodies;
    last?.frame.lease?.release();
    this.last = { bodies: frame.bodies, frame: quantized };
    this.work = { frame, quantized, shared: new SharedFrameWork(), stateVersion: this.source.gameStateVersion?.() ?? null, plain: new Map(), messages: new Map() };
    return this.work;
  }
}
