// Deterministic Jolt BodyID allocation: which (index, sequence number) every new body gets, decided in JS so a
// checkpoint can restore it. Jolt orders contacts by BodyID, so a rollback must hand out the very same ids again.
// Also mirrors Jolt's own per-index sequence counters, the only ones Jolt bumps itself (character inner bodies).

/** Bits of a Jolt BodyID: index in the low 23 bits, sequence number in the next 8 (bit 31 is Jolt's broad-phase bit). */
export const JOLT_INDEX_MASK = 0x7fffff;
const SEQ_SHIFT = 23;

/** Packs a Jolt body index and sequence number into the value BodyID(n) takes and GetIndexAndSequenceNumber returns. */
export function packJoltBodyId(index: number, sequence: number): number {
  return ((sequence & 0xff) * (1 << SEQ_SHIFT)) + (index & JOLT_INDEX_MASK);
}

/** The body index part of a packed Jolt BodyID. */
export function joltBodyIndex(joltId: number): number {
  return joltId & JOLT_INDEX_MASK;
}

/** The sequence number part of a packed Jolt BodyID. */
export function joltBodySequence(joltId: number): number {
  return (joltId >>> SEQ_SHIFT) & 0xff;
}

/** The allocator's state as plain data (part of every checkpoint). */
export interface BodyIdAllocatorState {
  /** Indices below this have been handed out at least once. */
  highWater: number;
  /** Free indices, the next one to reuse last. */
  free: number[];
  /** Last sequence number handed out per index, for indices below highWater. */
  sequences: Uint8Array;
}

/** Hands out Jolt BodyIDs: reuses freed indices last-in first-out, bumping the index's sequence number. */
export class BodyIdAllocator {
  readonly capacity: number;
  private highWater = 0;
  private free: number[] = [];
  private readonly sequences: Uint8Array;
  private readonly live: Uint8Array;

  constructor(capacity: number) {
    this.capacity = capacity;
    this.sequences = new Uint8Array(capacity);
    this.live = new Uint8Array(capacity);
  }

  /** The next BodyID (packed); throws when every index is in use. */
  allocate(): number {
    let index: number;
    if (this.free.length > 0) index = this.free.pop()!;
    else if (this.highWater < this.capacity) index = this.highWater++;
    else throw new Error(`BodyIdAllocator: all ${this.capacity} body slots are in use`);
    const seq = (this.sequences[index] + 1) & 0xff;
    this.sequences[index] = seq;
    this.live[index] = 1;
    return packJoltBodyId(index, seq);
  }

  /** Marks a specific BodyID as in use (a body recreated by a checkpoint restore); its index must be free. */
  claim(joltId: number): void {
    const index = joltBodyIndex(joltId);
    if (index >= this.capacity) throw new Error(`BodyIdAllocator: body index ${index} is beyond the capacity ${this.capacity}`);
    if (this.live[index]) throw new Error(`BodyIdAllocator: body index ${index} is already in use`);
    while (this.highWater <= index) this.free.unshift(this.highWater++);
    const at = this.free.indexOf(index);
    if (at >= 0) this.free.splice(at, 1);
    this.sequences[index] = joltBodySequence(joltId);
    this.live[index] = 1;
  }

  /** Returns a body's index for reuse. */
  release(joltId: number): void {
    const index = joltBodyIndex(joltId);
    if (index >= this.capacity || !this.live[index]) throw new Error(`BodyIdAllocator: body index ${index} is not in use`);
    this.live[index] = 0;
    this.free.push(index);
  }

  /** A copy of the state. */
  save(): BodyIdAllocatorState {
    return { highWater: this.highWater, free: this.free.slice(), sequences: this.sequences.slice(0, this.highWater) };
  }

  /** Replaces the state with a saved one; `liveIndices` are the indices in use after the restore. */
  restore(state: BodyIdAllocatorState, liveIndices: Iterable<number>): void {
    const { highWater, free, sequences } = state;
    if (!Number.isInteger(highWater) || highWater < 0 || highWater > this.capacity || sequences.length !== highWater) {
      throw new Error(`BodyIdAllocator.restore: bad state (highWater ${highWater}, capacity ${this.capacity})`);
    }
    for (const i of free) {
      if (!Number.isInteger(i) || i < 0 || i >= highWater) throw new Error(`BodyIdAllocator.restore: free index ${i} out of range`);
    }
    this.highWater = highWater;
    this.free = free.slice();
    this.sequences.fill(0);
    this.sequences.set(sequences);
    this.live.fill(0);
    for (const i of liveIndices) this.live[i] = 1;
  }

  /** Whether an index is in use. */
  isLive(index: number): boolean {
    return this.live[index] === 1;
  }
}
