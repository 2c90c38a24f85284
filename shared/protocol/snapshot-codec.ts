// The snapshot bit layout: a QuantizedFrame encoded as a delta against a baseline frame the client acknowledged
// (or against nothing: a full snapshot), and its exact inverse. Layout documented in docs/protocol.md.
import { BitReader, BitWriter, bestExpGolombOrder, zigzag } from './bit-stream.ts';
import type { SnapshotFormat } from './quantization.ts';
import { BODY_Q_STRIDE, CHARACTER_Q_STRIDE, emptyFrame, type QuantizedFrame } from './snapshot-frame.ts';

/** Exp-Golomb orders of fixed-order fields. */
const K_BASELINE_AGE = 3;
const K_BODY_COUNT = 8;
const K_CHARACTER_COUNT = 2;
const K_LIST_COUNT = 3;
const K_CHAR_BODY_ID = 4;
const K_CHAR_POS = 3;
const K_CHAR_VEL = 3;
const K_CHAR_ANGLE = 4;
const VELOCITY_OFFSET = 32767;
const PITCH_OFFSET = 16384;
const EMPTY = emptyFrame(0);

/** What the first bytes of a snapshot say. */
export interface SnapshotHeader {
  tick: number;
  /** The tick of the frame the delta applies to; null for a full snapshot. */
  baselineTick: number | null;
  bodyCount: number;
  characterCount: number;
}

function writeGapList(w: BitWriter, values: number[]): void {
  w.writeExpGolomb(values.length, K_LIST_COUNT);
  if (values.length === 0) return;
  const gaps = new Array<number>(values.length);
  gaps[0] = values[0];
  for (let i = 1; i < values.length; i++) gaps[i] = values[i] - values[i - 1] - 1;
  const k = bestExpGolombOrder(gaps, gaps.length);
  w.writeBits(k, 4);
  for (const g of gaps) w.writeExpGolomb(g, k);
}

function readGapList(r: BitReader, maxCount: number, what: string): number[] {
  const count = r.readExpGolomb(K_LIST_COUNT);
  if (count > maxCount || count > r.remainingBits) throw new Error(`snapshot corrupt: ${count} ${what} (at most ${maxCount})`);
  const out = new Array<number>(count);
  if (count === 0) return out;
  const k = r.readBits(4);
  let prev = -1;
  for (let i = 0; i < count; i++) {
    prev = prev + 1 + r.readExpGolomb(k);
    out[i] = prev;
  }
  return out;
}

function wrapYawDelta(d: number): number {
  const m = ((d % 65536) + 65536) % 65536;
  return m >= 32768 ? m - 65536 : m;
}

/** Encodes `frame` as a delta against `baseline` (null: a full snapshot). The baseline must be older than the frame. */
export function encodeSnapshot(format: SnapshotFormat, frame: QuantizedFrame, baseline: QuantizedFrame | null): Uint8Array {
  if (baseline !== null && !(baseline.tick < frame.tick)) throw new Error(`encodeSnapshot: baseline tick ${baseline.tick} must be older than frame tick ${frame.tick}`);
  const base = baseline ?? EMPTY;
  const w = new BitWriter(64 + frame.bodyIds.length * 4);
  w.writeBits(frame.tick, 32);
  w.writeBool(baseline !== null);
  if (baseline !== null) w.writeExpGolomb(frame.tick - baseline.tick - 1, K_BASELINE_AGE);
  w.writeExpGolomb(frame.bodyIds.length, K_BODY_COUNT);
  w.writeExpGolomb(frame.playerIds.length, K_CHARACTER_COUNT);
  encodeBodies(format, w, frame, base);
  encodeCharacters(format, w, frame, base);
  return w.finish();
}

/** How a frame's rows (sorted ids, `stride` values each) differ from the baseline's. */
interface RowDiff {
  /** Baseline row indices whose id is gone. */
  removed: number[];
  /** Ids new in the frame, and their row indices there. */
  spawnedIds: number[];
  spawnedIdx: number[];
  /** Row indices (frame, baseline) of ids present in both whose values differ. */
  changed: number[];
  changedBase: number[];
}

/** Merges two sorted id lists and compares the rows of ids present in both. */
function diffRows(ids: ArrayLike<number>, baseIds: ArrayLike<number>, cur: ArrayLike<number>, old: ArrayLike<number>, stride: number): RowDiff {
  const d: RowDiff = { removed: [], spawnedIds: [], spawnedIdx: [], changed: [], changedBase: [] };
  let i = 0;
  let j = 0;
  const n = ids.length;
  const m = baseIds.length;
  while (i < n || j < m) {
    if (j >= m || (i < n && ids[i] < baseIds[j])) {
      d.spawnedIds.push(ids[i]);
      d.spawnedIdx.push(i++);
    } else if (i >= n || baseIds[j] < ids[i]) {
      d.removed.push(j++);
    } else {
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

function encodeBodies(format: SnapshotFormat, w: BitWriter, frame: QuantizedFrame, base: QuantizedFrame): void {
  const cur = frame.bodies;
  const old = base.bodies;
  const { removed, spawnedIds, spawnedIdx, changed, changedBase } = diffRows(frame.bodyIds, base.bodyIds, cur, old, BODY_Q_STRIDE);
  writeGapList(w, removed);
  writeGapList(w, spawnedIds);
  writeGapList(w, changed);

  // Exp-Golomb orders for the deltas, chosen to minimise this snapshot's size.
  const posDeltas: number[] = [];
  const rotDeltas: number[] = [];
  for (let c = 0; c < changed.length; c++) {
    const a = changed[c] * BODY_Q_STRIDE;
    const b = changedBase[c] * BODY_Q_STRIDE;
    if (cur[a] !== old[b] || cur[a + 1] !== old[b + 1] || cur[a + 2] !== old[b + 2]) {
      for (let f = 0; f < 3; f++) posDeltas.push(zigzag(cur[a + f] - old[b + f]));
    }
    if (cur[a + 3] === old[b + 3] && (cur[a + 4] !== old[b + 4] || cur[a + 5] !== old[b + 5] || cur[a + 6] !== old[b + 6])) {
      for (let f = 4; f < 7; f++) rotDeltas.push(zigzag(cur[a + f] - old[b + f]));
    }
  }
  const kPos = bestExpGolombOrder(posDeltas, posDeltas.length);
  const kRot = bestExpGolombOrder(rotDeltas, rotDeltas.length);
  if (changed.length > 0) {
    w.writeBits(kPos, 4);
    w.writeBits(kRot, 4);
  }
  const pb = format.positionBits;
  const rb = format.rotationBits;
  for (const idx of spawnedIdx) {
    const a = idx * BODY_Q_STRIDE;
    w.writeBits(cur[a], pb[0]);
    w.writeBits(cur[a + 1], pb[1]);
    w.writeBits(cur[a + 2], pb[2]);
    w.writeBits(cur[a + 3], 2);
    w.writeBits(cur[a + 4], rb);
    w.writeBits(cur[a + 5], rb);
    w.writeBits(cur[a + 6], rb);
    w.writeBits(cur[a + 7], 1);
  }
  for (let c = 0; c < changed.length; c++) {
    const a = changed[c] * BODY_Q_STRIDE;
    const b = changedBase[c] * BODY_Q_STRIDE;
    const posChanged = cur[a] !== old[b] || cur[a + 1] !== old[b + 1] || cur[a + 2] !== old[b + 2];
    w.writeBool(posChanged);
    if (posChanged) for (let f = 0; f < 3; f++) w.writeSignedExpGolomb(cur[a + f] - old[b + f], kPos);
    const rotChanged = cur[a + 3] !== old[b + 3] || cur[a + 4] !== old[b + 4] || cur[a + 5] !== old[b + 5] || cur[a + 6] !== old[b + 6];
    w.writeBool(rotChanged);
    if (rotChanged) {
      const sameIndex = cur[a + 3] === old[b + 3];
      w.writeBool(sameIndex);
      if (sameIndex) {
        for (let f = 4; f < 7; f++) w.writeSignedExpGolomb(cur[a + f] - old[b + f], kRot);
      } else {
        w.writeBits(cur[a + 3], 2);
        for (let f = 4; f < 7; f++) w.writeBits(cur[a + f], rb);
      }
    }
    w.writeBits(cur[a + 7], 1);
  }
}

function encodeCharacters(format: SnapshotFormat, w: BitWriter, frame: QuantizedFrame, base: QuantizedFrame): void {
  const cur = frame.characters;
  const old = base.characters;
  const { removed, spawnedIds, spawnedIdx, changed, changedBase } = diffRows(frame.playerIds, base.playerIds, cur, old, CHARACTER_Q_STRIDE);
  writeGapList(w, removed);
  writeGapList(w, spawnedIds);
  writeGapList(w, changed);
  const pb = format.positionBits;
  for (const idx of spawnedIdx) {
    const a = idx * CHARACTER_Q_STRIDE;
    w.writeExpGolomb(cur[a], K_CHAR_BODY_ID);
    w.writeBits(cur[a + 1], pb[0]);
    w.writeBits(cur[a + 2], pb[1]);
    w.writeBits(cur[a + 3], pb[2]);
    for (let f = 4; f < 7; f++) w.writeBits(cur[a + f] + VELOCITY_OFFSET, 16);
    w.writeBits(cur[a + 7], 16);
    w.writeBits(cur[a + 8] + PITCH_OFFSET, 16);
    w.writeBits(cur[a + 9], 2);
    w.writeBits(cur[a + 10], 8);
  }
  for (let c = 0; c < changed.length; c++) {
    const a = changed[c] * CHARACTER_Q_STRIDE;
    const b = changedBase[c] * CHARACTER_Q_STRIDE;
    const bodyChanged = cur[a] !== old[b];
    w.writeBool(bodyChanged);
    if (bodyChanged) w.writeExpGolomb(cur[a], K_CHAR_BODY_ID);
    const posChanged = cur[a + 1] !== old[b + 1] || cur[a + 2] !== old[b + 2] || cur[a + 3] !== old[b + 3];
    w.writeBool(posChanged);
    if (posChanged) for (let f = 1; f < 4; f++) w.writeSignedExpGolomb(cur[a + f] - old[b + f], K_CHAR_POS);
    const velChanged = cur[a + 4] !== old[b + 4] || cur[a + 5] !== old[b + 5] || cur[a + 6] !== old[b + 6];
    w.writeBool(velChanged);
    if (velChanged) for (let f = 4; f < 7; f++) w.writeSignedExpGolomb(cur[a + f] - old[b + f], K_CHAR_VEL);
    const yawChanged = cur[a + 7] !== old[b + 7];
    w.writeBool(yawChanged);
    if (yawChanged) w.writeSignedExpGolomb(wrapYawDelta(cur[a + 7] - old[b + 7]), K_CHAR_ANGLE);
    const pitchChanged = cur[a + 8] !== old[b + 8];
    w.writeBool(pitchChanged);
    if (pitchChanged) w.writeSignedExpGolomb(cur[a + 8] - old[b + 8], K_CHAR_ANGLE);
    const groundChanged = cur[a + 9] !== old[b + 9];
    w.writeBool(groundChanged);
    if (groundChanged) w.writeBits(cur[a + 9], 2);
    const buttonsChanged = cur[a + 10] !== old[b + 10];
    w.writeBool(buttonsChanged);
    if (buttonsChanged) w.writeBits(cur[a + 10], 8);
  }
}

function readHeader(r: BitReader): SnapshotHeader {
  const tick = r.readBits(32);
  const hasBaseline = r.readBool();
  let baselineTick: number | null = null;
  if (hasBaseline) {
    const age = r.readExpGolomb(K_BASELINE_AGE) + 1;
    if (age > tick) throw new Error(`snapshot corrupt: baseline ${age} ticks before tick ${tick}`);
    baselineTick = tick - age;
  }
  const bodyCount = r.readExpGolomb(K_BODY_COUNT);
  const characterCount = r.readExpGolomb(K_CHARACTER_COUNT);
  return { tick, baselineTick, bodyCount, characterCount };
}

/** Reads only the header (tick, baseline) of an encoded snapshot; throws a clear Error on truncated bytes. */
export function readSnapshotHeader(bytes: Uint8Array): SnapshotHeader {
  return readHeader(new BitReader(bytes));
}

/**
 * Decodes a snapshot into the exact frame the server encoded. `baselineFor(tick)` returns a frame decoded earlier;
 * throws a clear Error when the baseline is unknown or the bytes are corrupt or truncated.
 */
export function decodeSnapshot(format: SnapshotFormat, bytes: Uint8Array, baselineFor: (tick: number) => QuantizedFrame | undefined): QuantizedFrame {
  const r = new BitReader(bytes);
  const header = readHeader(r);
  let base = EMPTY;
  if (header.baselineTick !== null) {
    const found = baselineFor(header.baselineTick);
    if (found === undefined) throw new Error(`snapshot ${header.tick}: baseline tick ${header.baselineTick} is not in the decoder's history`);
    if (found.tick !== header.baselineTick) throw new Error(`snapshot ${header.tick}: baseline lookup returned tick ${found.tick}, wanted ${header.baselineTick}`);
    base = found;
  }
  const { bodyIds, bodies } = decodeBodies(format, r, header, base);
  const { playerIds, characters } = decodeCharacters(format, r, header, base);
  if (r.remainingBits >= 8) throw new Error(`snapshot ${header.tick} corrupt: ${r.remainingBits} bits left after the last field`);
  if (r.readBits(r.remainingBits) !== 0) throw new Error(`snapshot ${header.tick} corrupt: non-zero padding`);
  return { tick: header.tick, bodyIds, bodies, playerIds, characters };
}

/** Merges kept baseline entries and spawned ids; returns for each current index its baseline index or −1. */
function mergeIds(baseIds: Uint32Array, removed: number[], spawned: number[], count: number, what: string, tick: number): { ids: Uint32Array; fromBase: Int32Array } {
  const keptCount = baseIds.length - removed.length;
  if (keptCount + spawned.length !== count) {
    throw new Error(`snapshot ${tick} corrupt: ${what} count ${count} ≠ ${keptCount} kept + ${spawned.length} spawned`);
  }
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
      if (spawned[si] > 0x7fff_ffff) throw new Error(`snapshot ${tick} corrupt: ${what} id ${spawned[si]} out of range`);
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

function checkRange(value: number, lo: number, hi: number, what: string, tick: number): number {
  if (!(value >= lo && value <= hi)) throw new Error(`snapshot ${tick} corrupt: ${what} ${value} outside [${lo}, ${hi}]`);
  return value;
}

function decodeBodies(format: SnapshotFormat, r: BitReader, h: SnapshotHeader, base: QuantizedFrame): { bodyIds: Uint32Array; bodies: Int32Array } {
  const removed = readGapList(r, base.bodyIds.length, 'removed bodies');
  const spawned = readGapList(r, h.bodyCount, 'spawned bodies');
  const changed = readGapList(r, h.bodyCount, 'changed bodies');
  const { ids, fromBase } = mergeIds(base.bodyIds, removed, spawned, h.bodyCount, 'body', h.tick);
  const out = new Int32Array(h.bodyCount * BODY_Q_STRIDE);
  const old = base.bodies;
  for (let i = 0; i < h.bodyCount; i++) {
    const j = fromBase[i];
    if (j < 0) continue;
    const a = i * BODY_Q_STRIDE;
    const b = j * BODY_Q_STRIDE;
    for (let f = 0; f < BODY_Q_STRIDE; f++) out[a + f] = old[b + f];
  }
  let kPos = 0;
  let kRot = 0;
  if (changed.length > 0) {
    kPos = r.readBits(4);
    kRot = r.readBits(4);
  }
  const pb = format.positionBits;
  const steps = format.positionSteps;
  const rb = format.rotationBits;
  const rmax = format.rotationMax;
  for (let i = 0; i < h.bodyCount; i++) {
    if (fromBase[i] >= 0) continue;
    const a = i * BODY_Q_STRIDE;
    out[a] = checkRange(r.readBits(pb[0]), 0, steps[0], 'position x', h.tick);
    out[a + 1] = checkRange(r.readBits(pb[1]), 0, steps[1], 'position y', h.tick);
    out[a + 2] = checkRange(r.readBits(pb[2]), 0, steps[2], 'position z', h.tick);
    out[a + 3] = r.readBits(2);
    for (let f = 4; f < 7; f++) out[a + f] = checkRange(r.readBits(rb), 0, rmax, 'rotation component', h.tick);
    out[a + 7] = r.readBits(1);
  }
  for (const idx of changed) {
    if (idx >= h.bodyCount || fromBase[idx] < 0) throw new Error(`snapshot ${h.tick} corrupt: changed body index ${idx} is not a kept body`);
    const a = idx * BODY_Q_STRIDE;
    if (r.readBool()) {
      for (let f = 0; f < 3; f++) out[a + f] = checkRange(out[a + f] + r.readSignedExpGolomb(kPos), 0, steps[f], 'position', h.tick);
    }
    if (r.readBool()) {
      if (r.readBool()) {
        for (let f = 4; f < 7; f++) out[a + f] = checkRange(out[a + f] + r.readSignedExpGolomb(kRot), 0, rmax, 'rotation component', h.tick);
      } else {
        out[a + 3] = r.readBits(2);
        for (let f = 4; f < 7; f++) out[a + f] = checkRange(r.readBits(rb), 0, rmax, 'rotation component', h.tick);
      }
    }
    out[a + 7] = r.readBits(1);
  }
  return { bodyIds: ids, bodies: out };
}

function decodeCharacters(format: SnapshotFormat, r: BitReader, h: SnapshotHeader, base: QuantizedFrame): { playerIds: Uint32Array; characters: Int32Array } {
  const removed = readGapList(r, base.playerIds.length, 'removed characters');
  const spawned = readGapList(r, h.characterCount, 'spawned characters');
  const changed = readGapList(r, h.characterCount, 'changed characters');
  const { ids, fromBase } = mergeIds(base.playerIds, removed, spawned, h.characterCount, 'character', h.tick);
  const out = new Int32Array(h.characterCount * CHARACTER_Q_STRIDE);
  const old = base.characters;
  for (let i = 0; i < h.characterCount; i++) {
    const j = fromBase[i];
    if (j < 0) continue;
    const a = i * CHARACTER_Q_STRIDE;
    const b = j * CHARACTER_Q_STRIDE;
    for (let f = 0; f < CHARACTER_Q_STRIDE; f++) out[a + f] = old[b + f];
  }
  const pb = format.positionBits;
  const steps = format.positionSteps;
  const t = h.tick;
  for (let i = 0; i < h.characterCount; i++) {
    if (fromBase[i] >= 0) continue;
    const a = i * CHARACTER_Q_STRIDE;
    out[a] = r.readExpGolomb(K_CHAR_BODY_ID);
    for (let f = 0; f < 3; f++) out[a + 1 + f] = checkRange(r.readBits(pb[f]), 0, steps[f], 'character position', t);
    for (let f = 4; f < 7; f++) out[a + f] = checkRange(r.readBits(16) - VELOCITY_OFFSET, -VELOCITY_OFFSET, VELOCITY_OFFSET, 'character velocity', t);
    out[a + 7] = r.readBits(16);
    out[a + 8] = checkRange(r.readBits(16) - PITCH_OFFSET, -PITCH_OFFSET, PITCH_OFFSET, 'character pitch', t);
    out[a + 9] = r.readBits(2);
    out[a + 10] = r.readBits(8);
  }
  for (const idx of changed) {
    if (idx >= h.characterCount || fromBase[idx] < 0) throw new Error(`snapshot ${t} corrupt: changed character index ${idx} is not a kept character`);
    const a = idx * CHARACTER_Q_STRIDE;
    if (r.readBool()) out[a] = r.readExpGolomb(K_CHAR_BODY_ID);
    if (r.readBool()) for (let f = 1; f < 4; f++) out[a + f] = checkRange(out[a + f] + r.readSignedExpGolomb(K_CHAR_POS), 0, steps[f - 1], 'character position', t);
    if (r.readBool()) {
      for (let f = 4; f < 7; f++) out[a + f] = checkRange(out[a + f] + r.readSignedExpGolomb(K_CHAR_VEL), -VELOCITY_OFFSET, VELOCITY_OFFSET, 'character velocity', t);
    }
    if (r.readBool()) out[a + 7] = (((out[a + 7] + r.readSignedExpGolomb(K_CHAR_ANGLE)) % 65536) + 65536) % 65536;
    if (r.readBool()) out[a + 8] = checkRange(out[a + 8] + r.readSignedExpGolomb(K_CHAR_ANGLE), -PITCH_OFFSET, PITCH_OFFSET, 'character pitch', t);
    if (r.readBool()) out[a + 9] = r.readBits(2);
    if (r.readBool()) out[a + 10] = r.readBits(8);
  }
  return { playerIds: ids, characters: out };
}
