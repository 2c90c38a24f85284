// Reused storage for a room's quantized frames: one buffer per frame (bodies, body ids, characters, player ids), given
// back once nothing holds the frame. Holders (the room's snapshot fan-out, each client's encoder history) retain and
// release the frames they keep; a frame no holder retained is never reused. A buffer's generation changes on each
// reuse, so a frame read after its buffer went back shows as dead (frameIsLive) instead of as another tick's numbers.
import { BODY_Q_STRIDE, CHARACTER_Q_STRIDE, type QuantizedFrame } from './snapshot-frame.ts';

/** Free buffers kept for reuse (a room needs about one a snapshot tick; more only come back after a burst). */
const MAX_FREE = 4;
/** Room a new buffer leaves for bodies and characters beyond the frame it is made for. */
const HEADROOM = 1.25;

/** One pooled buffer and the counts it has room for. */
interface Slot {
  buffer: ArrayBuffer;
  bodies: number;
  characters: number;
  /** Bumped when the slot is handed out again: frames made before it are dead. */
  generation: number;
}

/** A pooled frame's tie to its buffer: how many holders keep it, and which use of the buffer it is. */
export class FrameLease {
  private readonly pool: QuantizedFramePool;
  readonly slot: Slot;
  readonly generation: number;
  private holders = 0;

  constructor(pool: QuantizedFramePool, slot: Slot) {
    this.pool = pool;
    this.slot = slot;
    this.generation = slot.generation;
  }

  /** Whether the frame's arrays still hold its own numbers (its buffer was not handed out again). */
  get live(): boolean {
    return this.slot.generation === this.generation;
  }

  /** A holder keeps the frame (until its release()). */
  retain(): void {
    if (!this.live) throw new Error('FrameLease: retain of a frame whose buffer was reused');
    this.holders++;
  }

  /** A holder lets go; the last one gives the buffer back to the pool. */
  release(): void {
    if (!this.live) return; // its buffer already went back (a holder released twice); nothing of it is held
    if (this.holders <= 0) throw new Error('FrameLease: release without a matching retain');
    if (--this.holders === 0) this.pool.giveBack(this.slot);
  }
}

/** The arrays of a frame about to be quantized, exactly sized views into one buffer, and its lease. */
export interface PooledArrays {
  bodyIds: Uint32Array;
  bodies: Int32Array;
  playerIds: Uint32Array;
  characters: Int32Array;
  lease: FrameLease;
}

/** Buffers for quantized frames, reused once every holder released the frame that had one. */
export class QuantizedFramePool {
  private readonly free: Slot[] = [];
  /** Buffers handed out since creation, and how many of them were reused ones (for tests and figures). */
  readonly counts = { taken: 0, reused: 0 };

  /** Arrays for a frame of `bodies` bodies and `characters` characters (zeroed only when the buffer is new). */
  take(bodies: number, characters: number): PooledArrays {
    let slot: Slot | undefined;
    while (this.free.length > 0) {
      const s = this.free.pop()!;
      if (s.bodies >= bodies && s.characters >= characters) {
        slot = s;
        break;
      }
    }
    this.counts.taken++;
    if (slot === undefined) {
      const b = Math.ceil(bodies * HEADROOM) + 8;
      const c = Math.ceil(characters * HEADROOM) + 4;
      slot = { buffer: new ArrayBuffer((b * (BODY_Q_STRIDE + 1) + c * (CHARACTER_Q_STRIDE + 1)) * 4), bodies: b, characters: c, generation: 0 };
    }
    else this.counts.reused++;
    const { buffer } = slot;
    let at = 0;
    const bodyQ = new Int32Array(buffer, at, bodies * BODY_Q_STRIDE);
    at += slot.bodies * BODY_Q_STRIDE * 4;
    const bodyIds = new Uint32Array(buffer, at, bodies);
    at += slot.bodies * 4;
    const charQ = new Int32Array(buffer, at, characters * CHARACTER_Q_STRIDE);
    at += slot.characters * CHARACTER_Q_STRIDE * 4;
    const playerIds = new Uint32Array(buffer, at, characters);
    return { bodyIds, bodies: bodyQ, playerIds, characters: charQ, lease: new FrameLease(this, slot) };
  }

  /** Called by a lease when its last holder let go. */
  giveBack(slot: Slot): void {
    slot.generation++; // frames of this use are dead from now on, even before the buffer is handed out again
    if (this.free.length < MAX_FREE) this.free.push(slot);
  }
}

/** Whether a frame's numbers are its own: true for frames outside a pool, and for pooled ones whose buffer was not given back. */
export function frameIsLive(frame: QuantizedFrame): boolean {
  return frame.lease === undefined || frame.lease.live;
}
