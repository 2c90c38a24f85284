// Row bookkeeping shared by the body and character sections of the snapshot codec: diffing a frame's sorted rows
// against the baseline's, the range-coded id and index lists that describe the difference, and merging them back.
import { UIntModel, type RangeDecoder, type RangeEncoder } from './range-coder.ts';

/** How a frame's rows (sorted ids, `stride` values each) differ from the baseline's. */
export interface RowDiff {
  /** Baseline row indices whose id is gone. */
  removed: number[];
  /** Ids new in the frame, and their row indices there. */
  spawnedIds: number[];
  spawnedIdx: number[];
  /** Row indices (frame, baseline) of ids present in both whose values differ. */
  changed: number[];
  changedBase: number[];
  /** For each frame row, its baseline row index, or −1 for a spawned row. */
  fromBase: Int32Array;
}

/** Merges two sorted id lists and compares the rows of ids present in both. */
export function diffRows(ids: ArrayLike<number>, baseIds: ArrayLike<number>, cur: ArrayLike<number>, old: ArrayLike<number>, stride: number): RowDiff {
  const d: RowDiff = { removed: [], spawnedIds: [], spawnedIdx: [], changed: [], changedBase: [], fromBase: new Int32Array(ids.length) };
  let i = 0;
  let j = 0;
  const n = ids.length;
  const m = baseIds.length;
  while (i < n || j < m) {
    if (j >= m || (i < n && ids[i] < baseIds[j])) {
      d.spawnedIds.push(ids[i]);
      d.fromBase[i] = -1;
      d.spawnedIdx.push(i++);
    } else if (i >= n || baseIds[j] < ids[i]) {
      d.removed.push(j++);
    } else {
      d.fromBase[i] = j;
      const a = i * stride;
      const b = j * stride;
      for (let f = 0; f < stride; f++) {
        if (cur[a + f] !== old[b + f]) {
          d.changed.push(i);
          d.changedBase.push(j);
          break;
        }
      }
      i++;
      j++;
    }
  }
  return d;
}

/** Contexts of the list model: count and gaps of the removed, spawned and changed lists. */
const LIST_CONTEXTS = 6;

/** Codes ascending lists of non-negative integers as a count and the gaps between neighbours. */
export class ListCoder {
  private readonly model = new UIntModel(LIST_CONTEXTS);

  /** Forgets the statistics. */
  reset(): void {
    this.model.reset();
  }

  /** `kind`: 0 removed, 1 spawned, 2 changed. */
  encode(enc: RangeEncoder, values: readonly number[], kind: number): void {
    this.model.encode(enc, values.length, kind * 2);
    let prev = -1;
    for (const v of values) {
      this.model.encode(enc, v - prev - 1, kind * 2 + 1);
      prev = v;
    }
  }

  /** Reads a list of at most `maxCount` values, each ≤ maxValue; throws a clear Error beyond either. */
  decode(dec: RangeDecoder, kind: number, maxCount: number, maxValue: number, what: string, tick: number): number[] {
    const count = this.model.decode(dec, kind * 2);
    if (count > maxCount) throw new Error(`snapshot ${tick} corrupt: ${count} ${what} (at most ${maxCount})`);
    const out = new Array<number>(count);
    let prev = -1;
    for (let i = 0; i < count; i++) {
      prev = prev + 1 + this.model.decode(dec, kind * 2 + 1);
      if (prev > maxValue) throw new Error(`snapshot ${tick} corrupt: ${what} value ${prev} above ${maxValue}`);
      out[i] = prev;
    }
    return out;
  }
}

/** Merges kept baseline entries and spawned ids; returns for each current index its baseline index or −1. */
export function mergeIds(baseIds: Uint32Array, removed: number[], spawned: number[], what: string, tick: number): { ids: Uint32Array; fromBase: Int32Array } {
  const count = baseIds.length - removed.length + spawned.length;
  const ids = new Uint32Array(count);
  const fromBase = new Int32Array(count);
  let ri = 0;
  let si = 0;
  let out = 0;
  for (let j = 0; j <= baseIds.length; j++) {
    const isEnd = j === baseIds.length;
    if (!isEnd && ri < removed.length && removed[ri] === j) {
      ri++;
      continue;
    }
    while (si < spawned.length && (isEnd || spawned[si] < baseIds[j])) {
      ids[out] = spawned[si++];
      fromBase[out++] = -1;
    }
    if (isEnd) break;
    if (si < spawned.length && spawned[si] === baseIds[j]) throw new Error(`snapshot ${tick} corrupt: ${what} ${baseIds[j]} spawned while present`);
    ids[out] = baseIds[j];
    fromBase[out++] = j;
  }
  if (ri !== removed.length) throw new Error(`snapshot ${tick} corrupt: removed ${what} index out of range`);
  return { ids, fromBase };
}

/** Copies the kept rows of the baseline into a new row array (`unchangedRows`: no row came or went, one copy). */
export function keptRows(fromBase: Int32Array, old: Int32Array, stride: number, unchangedRows: boolean): Int32Array {
  if (unchangedRows) return old.slice();
  const out = new Int32Array(fromBase.length * stride);
  for (let i = 0; i < fromBase.length; i++) {
    const j = fromBase[i];
    if (j < 0) continue;
    const a = i * stride;
    const b = j * stride;
    for (let f = 0; f < stride; f++) out[a + f] = old[b + f];
  }
  return out;
}

/** Throws a clear Error when a decoded value is outside [lo, hi]. */
export function checkRange(value: number, lo: number, hi: number, what: string, tick: number): number {
  if (!(value >= lo && value <= hi)) throw new Error(`snapshot ${tick} corrupt: ${what} ${value} outside [${lo}, ${hi}]`);
  return value;
}
