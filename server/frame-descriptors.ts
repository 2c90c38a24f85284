// The descriptors a room's snapshots need, captured when a frame is taken rather than when it is sent: with
// --durability tick a frame goes out only after its tick is on disk, and by then a body in it (a bullet) may already
// be gone from the simulation. A removed body's descriptor is dropped once the tick that removed it has been sent.
import type { BodyDescriptor } from '../shared/sim/types.ts';

/** Descriptors of the bodies in frames taken and not yet all sent. */
export class FrameDescriptors {
  private readonly byId = new Map<number, BodyDescriptor>();

  /** Remembers the descriptor of every body in a frame being taken (`lookup` asks the simulation now). */
  capture(ids: ArrayLike<number>, count: number, skip: (id: number) => boolean, lookup: (id: number) => BodyDescriptor | null | undefined): void {
    for (let i = 0; i < count; i++) {
      const id = ids[i];
      if (this.byId.has(id) || skip(id)) continue;
      const d = lookup(id);
      if (d) this.byId.set(id, d);
    }
  }

  /** What to drop after the removing tick is sent: each removed body with the descriptor it had (its id may be reused). */
  removals(removedIds: readonly number[]): Array<[number, BodyDescriptor | undefined]> {
    return removedIds.map((id) => [id, this.byId.get(id)]);
  }

  /** Drops the descriptors of bodies whose removal has been sent, unless a new body took the id since. */
  release(removals: ReadonlyArray<[number, BodyDescriptor | undefined]>): void {
    for (const [id, d] of removals) if (d !== undefined && this.byId.get(id) === d) this.byId.delete(id);
  }

  /** The descriptor captured for a body. */
  get(id: number): BodyDescriptor | undefined {
    return this.byId.get(id);
  }
}
