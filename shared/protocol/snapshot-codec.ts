// The snapshot layout: a QuantizedFrame encoded as a delta against a baseline frame the client acknowledged (or
// against nothing: a full snapshot), and its exact inverse. A few plain header bits (tick, baseline, what changed),
// then the changes through an adaptive range coder whose statistics start afresh in every snapshot, so the bytes
// depend only on (format, frame, baseline). Layout documented in docs/protocol.md.
import { BitReader, BitWriter } from './bit-stream.ts';
import { IntModel, newProbs, RangeDecoder, RangeEncoder, resetProbs } from './range-coder.ts';
import type { SnapshotFormat } from './quantization.ts';
import { decodeCharacters, encodeCharacters } from './snapshot-characters.ts';
import { BODY_Q_STRIDE, CHARACTER_Q_STRIDE, emptyFrame, type QuantizedFrame } from './snapshot-frame.ts';
import { checkRange, diffRows, keptRows, ListCoder, mergeIds, type RowDiff } from './snapshot-rows.ts';

/** Exp-Golomb order of the baseline age. */
const K_BASELINE_AGE = 2;
/** Low tick bits a delta snapshot carries; the receiver completes them from the newest tick it decoded. */
export const DELTA_TICK_BITS = 16;
/** Largest tick − baseline tick a delta snapshot may have (older baselines: a full snapshot). */
export const MAX_BASELINE_AGE = (1 << (DELTA_TICK_BITS - 1)) - 1;
/** Most bodies or characters a snapshot may spawn per byte of its length (a decoder bound, far above any real one). */
const MAX_SPAWNS_PER_BYTE = 8;
const EMPTY = emptyFrame(0);
/** The flag context of 'this body, awake in the baseline, changed'. */
const AWAKE_CHANGED = 6;

/** What the first bytes of a snapshot say. */
export interface SnapshotHeader {
  tick: number;
  /** The tick of the frame the delta applies to; null for a full snapshot. */
  baselineTick: number | null;
  /** Whether any body, and any character, differs from the baseline. */
  bodiesChanged: boolean;
  charactersChanged: boolean;
  /** Where the range-coded changes start (bytes). */
  payloadOffset: number;
}

/**
 * The tick whose low DELTA_TICK_BITS bits are `low` nearest to `referenceTick` (the newest tick the receiver decoded;
 * a snapshot is at most MAX_BASELINE_AGE ticks newer than that, or delayed by less than that).
 */
export function completeTick(low: number, referenceTick: number): number {
  const span = 1 << DELTA_TICK_BITS;
  const half = span >>> 1;
  const tick = referenceTick + ((((low - referenceTick + half) % span) + span) % span) - half;
  return tick < 0 ? tick + span : tick;
}

/** Encodes `frame` as a delta against `baseline` (null: a full snapshot). The baseline must be older than the frame. */
export function encodeSnapshot(format: SnapshotFormat, frame: QuantizedFrame, baseline: QuantizedFrame | null): Uint8Array {
  if (baseline !== null && !(baseline.tick < frame.tick)) throw new Error(`encodeSnapshot: baseline tick ${baseline.tick} must be older than frame tick ${frame.tick}`);
  if (baseline !== null && frame.tick - baseline.tick > MAX_BASELINE_AGE) throw new Error(`encodeSnapshot: baseline tick ${baseline.tick} is more than ${MAX_BASELINE_AGE} ticks before ${frame.tick}`);
  const base = baseline ?? EMPTY;
  const bodyDiff = diffRows(frame.bodyIds, base.bodyIds, frame.bodies, base.bodies, BODY_Q_STRIDE);
  const charDiff = diffRows(frame.playerIds, base.playerIds, frame.characters, base.characters, CHARACTER_Q_STRIDE);
  const bodiesChanged = bodyDiff.removed.length + bodyDiff.spawnedIds.length + bodyDiff.changed.length > 0;
  const charactersChanged = charDiff.removed.length + charDiff.spawnedIds.length + charDiff.changed.length > 0;
  const w = new BitWriter(16);
  w.writeBool(baseline !== null);
  if (baseline === null) w.writeBits(frame.tick, 32);
  else {
    w.writeBits(frame.tick % (1 << DELTA_TICK_BITS), DELTA_TICK_BITS);
    w.writeExpGolomb(frame.tick - baseline.tick - 1, K_BASELINE_AGE);
  }
  w.writeBool(bodiesChanged);
  w.writeBool(charactersChanged);
  const header = w.finish();
  if (!bodiesChanged && !charactersChanged) return header;
  const enc = new RangeEncoder(64 + bodyDiff.changed.length * 12 + bodyDiff.spawnedIds.length * 10);
  if (bodiesChanged) encodeBodies(format, enc, frame, base, bodyDiff);
  if (charactersChanged) encodeCharacters(format, enc, frame, base, charDiff, baseline === null ? 0 : frame.tick - baseline.tick);
  const payload = enc.finish();
  const out = new Uint8Array(header.length + payload.length);
  out.set(header);
  out.set(payload, header.length);
  return out;
}

/** Adaptive statistics of the body section. */
class BodyModels {
  readonly lists = new ListCoder();
  /** Flags: position changed, rotation changed, same largest component, at-rest flipped (by the baseline's value), spawned at rest, awake body changed. */
  readonly flags = newProbs(7);
  /** Position deltas: x and z, y; each by how large the previous component of the body was. */
  readonly position = new IntModel(2 * 4);
  /** Rotation deltas: the first by how far the body moved, the others by the previous component's size. */
  readonly rotation = new IntModel(4);

  /** The models with fresh statistics (one set per direction, reused: allocating them costs more than coding). */
  fresh(): this {
    this.lists.reset();
    resetProbs(this.flags);
    this.position.reset();
    this.rotation.reset();
    return this;
  }
}

const encoderModels = new BodyModels();
const decoderModels = new BodyModels();

/** A context from the size class of the previous value: 0, 1–2, 3–14, more. */
function sizeClass(v: number): number {
  const a = v < 0 ? -v : v;
  return a === 0 ? 0 : a < 3 ? 1 : a < 15 ? 2 : 3;
}

function encodeBodies(format: SnapshotFormat, enc: RangeEncoder, frame: QuantizedFrame, base: QuantizedFrame, diff: RowDiff): void {
  const m = encoderModels.fresh();
  const cur = frame.bodies;
  const old = base.bodies;
  const { removed, spawnedIds, spawnedIdx, changed, changedBase, fromBase } = diff;
  m.lists.encode(enc, removed, 0);
  m.lists.encode(enc, spawnedIds, 1);
  // Which kept bodies changed: a modelled bit for each body awake in the baseline (most of them move), and the
  // ranks among the sleeping ones (few of them wake) as a list.
  const wokenRanks: number[] = [];
  let rank = 0;
  let next = 0;
  for (let i = 0; i < fromBase.length; i++) {
    const j = fromBase[i];
    if (j < 0) continue;
    while (next < changed.length && changed[next] < i) next++;
    const isChanged = next < changed.length && changed[next] === i ? 1 : 0;
    if (old[j * BODY_Q_STRIDE + 7] === 0) enc.encodeBit(m.flags, AWAKE_CHANGED, isChanged);
    else {
      if (isChanged === 1) wokenRanks.push(rank);
      rank++;
    }
  }
  m.lists.encode(enc, wokenRanks, 2);
  const pb = format.positionBits;
  const rb = format.rotationBits;
  for (const idx of spawnedIdx) {
    const a = idx * BODY_Q_STRIDE;
    enc.encodeDirect(cur[a], pb[0]);
    enc.encodeDirect(cur[a + 1], pb[1]);
    enc.encodeDirect(cur[a + 2], pb[2]);
    enc.encodeDirect(cur[a + 3], 2);
    for (let f = 4; f < 7; f++) enc.encodeDirect(cur[a + f], rb);
    enc.encodeBit(m.flags, 5, cur[a + 7]);
  }
  let prevX = 0;
  for (let c = 0; c < changed.length; c++) {
    const a = changed[c] * BODY_Q_STRIDE;
    const b = changedBase[c] * BODY_Q_STRIDE;
    const posChanged = cur[a] !== old[b] || cur[a + 1] !== old[b + 1] || cur[a + 2] !== old[b + 2];
    enc.encodeBit(m.flags, 0, posChanged ? 1 : 0);
    let moved = 0;
    if (posChanged) {
      const dx = cur[a] - old[b];
      const dy = cur[a + 1] - old[b + 1];
      moved = (dx < 0 ? -dx : dx) + (dy < 0 ? -dy : dy);
      m.position.encode(enc, dx, sizeClass(prevX));
      m.position.encode(enc, dy, 4 + sizeClass(dx));
      m.position.encode(enc, cur[a + 2] - old[b + 2], sizeClass(dx));
      prevX = dx;
    }
    const rotChanged = cur[a + 3] !== old[b + 3] || cur[a + 4] !== old[b + 4] || cur[a + 5] !== old[b + 5] || cur[a + 6] !== old[b + 6];
    enc.encodeBit(m.flags, 1, rotChanged ? 1 : 0);
    if (rotChanged) {
      const sameIndex = cur[a + 3] === old[b + 3];
      enc.encodeBit(m.flags, 2, sameIndex ? 1 : 0);
      if (sameIndex) {
        let ctx = sizeClass(moved);
        for (let f = 4; f < 7; f++) {
          const d = cur[a + f] - old[b + f];
          m.rotation.encode(enc, d, ctx);
          ctx = sizeClass(d);
        }
      } else {
        enc.encodeDirect(cur[a + 3], 2);
        for (let f = 4; f < 7; f++) enc.encodeDirect(cur[a + f], rb);
      }
    }
    enc.encodeBit(m.flags, 3 + old[b + 7], cur[a + 7] === old[b + 7] ? 0 : 1);
  }
}

function readHeader(bytes: Uint8Array, referenceTick: number | null): SnapshotHeader {
  const r = new BitReader(bytes);
  const hasBaseline = r.readBool();
  let tick: number;
  let baselineTick: number | null = null;
  if (!hasBaseline) tick = r.readBits(32);
  else {
    const low = r.readBits(DELTA_TICK_BITS);
    const age = r.readExpGolomb(K_BASELINE_AGE) + 1;
    if (referenceTick === null) throw new Error('snapshot: a delta snapshot needs the newest decoded tick to complete its tick');
    tick = completeTick(low, referenceTick);
    if (age > MAX_BASELINE_AGE || age > tick) throw new Error(`snapshot corrupt: baseline ${age} ticks before tick ${tick}`);
    baselineTick = tick - age;
  }
  const bodiesChanged = r.readBool();
  const charactersChanged = r.readBool();
  const payloadOffset = (r.bitPosition + 7) >>> 3;
  if (r.readBits(payloadOffset * 8 - r.bitPosition) !== 0) throw new Error(`snapshot ${tick} corrupt: non-zero padding`);
  if (!bodiesChanged && !charactersChanged && bytes.length > payloadOffset) throw new Error(`snapshot ${tick} corrupt: ${bytes.length - payloadOffset} bytes after an unchanged snapshot`);
  return { tick, baselineTick, bodiesChanged, charactersChanged, payloadOffset };
}

/**
 * Reads only the header of an encoded snapshot; throws a clear Error on truncated bytes. A delta snapshot carries
 * the low 16 bits of its tick: `referenceTick` (the newest snapshot tick the reader saw) completes them.
 */
export function readSnapshotHeader(bytes: Uint8Array, referenceTick: number | null = null): SnapshotHeader {
  return readHeader(bytes, referenceTick);
}

/**
 * Decodes a snapshot into the exact frame the server encoded. `baselineFor(tick)` returns a frame decoded earlier;
 * `referenceTick` is the newest tick decoded so far (null before the first). Throws a clear Error when the baseline
 * is unknown or the bytes are corrupt or truncated.
 */
export function decodeSnapshot(format: SnapshotFormat, bytes: Uint8Array, baselineFor: (tick: number) => QuantizedFrame | undefined, referenceTick: number | null = null): QuantizedFrame {
  const h = readHeader(bytes, referenceTick);
  let base = EMPTY;
  if (h.baselineTick !== null) {
    const found = baselineFor(h.baselineTick);
    if (found === undefined) throw new Error(`snapshot ${h.tick}: baseline tick ${h.baselineTick} is not in the decoder's history`);
    if (found.tick !== h.baselineTick) throw new Error(`snapshot ${h.tick}: baseline lookup returned tick ${found.tick}, wanted ${h.baselineTick}`);
    base = found;
  }
  if (!h.bodiesChanged && !h.charactersChanged) {
    return { tick: h.tick, bodyIds: base.bodyIds, bodies: base.bodies, playerIds: base.playerIds, characters: base.characters };
  }
  const dec = new RangeDecoder(bytes, h.payloadOffset);
  const maxSpawns = bytes.length * MAX_SPAWNS_PER_BYTE;
  const b = h.bodiesChanged ? decodeBodies(format, dec, h.tick, base, maxSpawns) : { bodyIds: base.bodyIds, bodies: base.bodies };
  const age = h.baselineTick === null ? 0 : h.tick - h.baselineTick;
  const c = h.charactersChanged ? decodeCharacters(format, dec, h.tick, base, maxSpawns, age) : { playerIds: base.playerIds, characters: base.characters };
  return { tick: h.tick, bodyIds: b.bodyIds, bodies: b.bodies, playerIds: c.playerIds, characters: c.characters };
}

/** The union of two ascending lists without common values, ascending. */
function mergeAscending(a: number[], b: number[]): number[] {
  if (b.length === 0) return a;
  const out: number[] = [];
  let i = 0;
  let j = 0;
  while (i < a.length || j < b.length) out.push(j >= b.length || (i < a.length && a[i] < b[j]) ? a[i++] : b[j++]);
  return out;
}

function decodeBodies(format: SnapshotFormat, dec: RangeDecoder, tick: number, base: QuantizedFrame, maxSpawns: number): { bodyIds: Uint32Array; bodies: Int32Array } {
  const m = decoderModels.fresh();
  const removed = m.lists.decode(dec, 0, base.bodyIds.length, base.bodyIds.length - 1, 'removed bodies', tick);
  const spawned = m.lists.decode(dec, 1, maxSpawns, 0x7fff_ffff, 'spawned bodies', tick);
  const count = base.bodyIds.length - removed.length + spawned.length;
  const { ids, fromBase } = mergeIds(base.bodyIds, removed, spawned, 'body', tick);
  const out = keptRows(fromBase, base.bodies, BODY_Q_STRIDE, removed.length === 0 && spawned.length === 0);
  // Kept bodies awake in the baseline carry a changed bit; the woken ones are ranks among those at rest.
  const awakeChanged: number[] = [];
  let sleeping = 0;
  for (let i = 0; i < count; i++) {
    if (fromBase[i] < 0) continue;
    if (out[i * BODY_Q_STRIDE + 7] === 0) {
      if (dec.decodeBit(m.flags, AWAKE_CHANGED) === 1) awakeChanged.push(i);
    } else sleeping++;
  }
  const wokenRanks = m.lists.decode(dec, 2, sleeping, sleeping - 1, 'woken bodies', tick);
  const woken: number[] = [];
  let rank = 0;
  for (let i = 0; i < count && woken.length < wokenRanks.length; i++) {
    if (fromBase[i] < 0 || out[i * BODY_Q_STRIDE + 7] === 0) continue;
    if (rank++ === wokenRanks[woken.length]) woken.push(i);
  }
  const changed = mergeAscending(awakeChanged, woken);
  const pb = format.positionBits;
  const steps = format.positionSteps;
  const rb = format.rotationBits;
  const rmax = format.rotationMax;
  for (let i = 0; i < count && spawned.length > 0; i++) {
    if (fromBase[i] >= 0) continue;
    const a = i * BODY_Q_STRIDE;
    for (let f = 0; f < 3; f++) out[a + f] = checkRange(dec.decodeDirect(pb[f]), 0, steps[f], 'position', tick);
    out[a + 3] = dec.decodeDirect(2);
    for (let f = 4; f < 7; f++) out[a + f] = checkRange(dec.decodeDirect(rb), 0, rmax, 'rotation component', tick);
    out[a + 7] = dec.decodeBit(m.flags, 5);
  }
  let prevX = 0;
  for (const idx of changed) {
    const a = idx * BODY_Q_STRIDE;
    let moved = 0;
    if (dec.decodeBit(m.flags, 0) === 1) {
      const dx = m.position.decode(dec, sizeClass(prevX));
      const dy = m.position.decode(dec, 4 + sizeClass(dx));
      moved = (dx < 0 ? -dx : dx) + (dy < 0 ? -dy : dy);
      const dz = m.position.decode(dec, sizeClass(dx));
      out[a] = checkRange(out[a] + dx, 0, steps[0], 'position', tick);
      out[a + 1] = checkRange(out[a + 1] + dy, 0, steps[1], 'position', tick);
      out[a + 2] = checkRange(out[a + 2] + dz, 0, steps[2], 'position', tick);
      prevX = dx;
    }
    if (dec.decodeBit(m.flags, 1) === 1) {
      if (dec.decodeBit(m.flags, 2) === 1) {
        let ctx = sizeClass(moved);
        for (let f = 4; f < 7; f++) {
          const d = m.rotation.decode(dec, ctx);
          out[a + f] = checkRange(out[a + f] + d, 0, rmax, 'rotation component', tick);
          ctx = sizeClass(d);
        }
      } else {
        out[a + 3] = dec.decodeDirect(2);
        for (let f = 4; f < 7; f++) out[a + f] = checkRange(dec.decodeDirect(rb), 0, rmax, 'rotation component', tick);
      }
    }
    const wasAtRest = out[a + 7];
    if (dec.decodeBit(m.flags, 3 + wasAtRest) === 1) out[a + 7] = 1 - wasAtRest;
  }
  return { bodyIds: ids, bodies: out };
}
