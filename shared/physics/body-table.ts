// The world's table of tracked bodies: stable id → handle, Jolt BodyID → handle, the sensor set and the ids in
// ascending order (the order bulk reads, clear() and checkpoints walk). Plain bookkeeping: touches no Jolt object.
import type { BodyHandle } from './body-handle.ts';

/** Tracked bodies of one world. */
export class BodyTable {
  /** Stable id → handle. */
  readonly byId = new Map<number, BodyHandle>();
  private readonly byJolt = new Map<number, BodyHandle>();
  private readonly sensorJoltIds = new Set<number>();
  /** Stable ids, ascending. Read-only for callers. */
  readonly sortedIds: number[] = [];

  /** Adds a handle (its id must be free). */
  add(handle: BodyHandle): void {
    this.byId.set(handle.id, handle);
    this.byJolt.set(handle.joltId, handle);
    if (handle.isSensor) this.sensorJoltIds.add(handle.joltId);
    const ids = this.sortedIds;
    if (ids.length === 0 || ids[ids.length - 1] < handle.id) ids.push(handle.id);
    else ids.splice(lowerBound(ids, handle.id), 0, handle.id);
  }

  /** Removes a handle. */
  delete(handle: BodyHandle): void {
    this.byId.delete(handle.id);
    this.byJolt.delete(handle.joltId);
    this.sensorJoltIds.delete(handle.joltId);
    const i = lowerBound(this.sortedIds, handle.id);
    if (this.sortedIds[i] === handle.id) this.sortedIds.splice(i, 1);
  }

  /** The handle for a stable id. */
  get(id: number): BodyHandle | undefined {
    return this.byId.get(id);
  }

  /** Whether `handle` is the live handle this table holds for its id. */
  owns(handle: BodyHandle | undefined): handle is BodyHandle {
    return !!handle && !handle.removed && this.byId.get(handle.id) === handle;
  }

  /** The handle for a Jolt BodyID (index + sequence number). */
  byJoltId(joltId: number): BodyHandle | undefined {
    return this.byJolt.get(joltId);
  }

  /** Whether a Jolt BodyID belongs to a sensor. */
  isSensorJoltId(joltId: number): boolean {
    return this.sensorJoltIds.has(joltId);
  }

  /** Number of tracked bodies. */
  get size(): number {
    return this.byId.size;
  }
}

function lowerBound(arr: readonly number[], value: number): number {
  let lo = 0;
  let hi = arr.length;
  while (lo < hi) {
    const mid = (lo + hi) >>> 1;
    if (arr[mid] < value) lo = mid + 1;
    else hi = mid;
  }
  return lo;
}
