// The character section of a snapshot: which characters came, went or changed, and each change through the range
// coder. A moving character's position is predicted from its baseline position and the mean of its baseline and new
// velocities over the baseline's age, so only the prediction error travels.
import { TICK_RATE_HZ } from '../tick-rate.ts';
import { IntModel, newProbs, resetProbs, UIntModel, type RangeDecoder, type RangeEncoder } from './range-coder.ts';
import { VELOCITY_LIMIT, VELOCITY_STEPS_PER_METRE_PER_SECOND, type SnapshotFormat } from './quantization.ts';
import { CHARACTER_Q_STRIDE, type QuantizedFrame } from './snapshot-frame.ts';
import { checkRange, keptRows, ListCoder, mergeIds, type RowDiff } from './snapshot-rows.ts';

const PITCH_LIMIT = 16384;
const YAW_STEPS = 65536;
/** Field groups with a changed flag each: body id, position, velocity, yaw, pitch, ground state, buttons. */
const GROUPS = 7;

class CharacterModels {
  readonly lists = new ListCoder();
  readonly changedFlags = newProbs(GROUPS);
  readonly bodyId = new UIntModel(1);
  /** Position prediction errors (x/z, y), velocity deltas (x/z, y), yaw and pitch deltas. */
  readonly position = new IntModel(2);
  readonly velocity = new IntModel(2);
  readonly angle = new IntModel(2);

  /** The models with fresh statistics (one set per direction, reused across snapshots). */
  fresh(): this {
    this.lists.reset();
    resetProbs(this.changedFlags);
    this.bodyId.reset();
    this.position.reset();
    this.velocity.reset();
    this.angle.reset();
    return this;
  }
}

const encoderModels = new CharacterModels();
const decoderModels = new CharacterModels();

/** Ground state code of a character standing on walkable ground. */
const ON_GROUND = 0;
/** Vertical velocity a character off the ground gains per tick under standard gravity (a prediction only). */
const FALL_STEPS_PER_TICK = (9.81 * VELOCITY_STEPS_PER_METRE_PER_SECOND) / TICK_RATE_HZ;

/**
 * Grid steps a character moves in `ageTicks` at the mean of two quantized velocities; none vertically while it stands
 * on the ground in both frames (its vertical velocity there is the ground's pull, not motion).
 */
function predictedSteps(format: SnapshotFormat, axis: number, v0: number, v1: number, ageTicks: number, grounded: boolean): number {
  if (axis === 1 && grounded) return 0;
  return Math.round(((v0 + v1) * ageTicks) / (2 * VELOCITY_STEPS_PER_METRE_PER_SECOND * TICK_RATE_HZ * format.positionStepMetres[axis]));
}

/** The change of vertical velocity predicted for a character off the ground in both frames: falling. */
function predictedFall(ground0: number, ground1: number, ageTicks: number): number {
  return ground0 !== ON_GROUND && ground1 !== ON_GROUND ? -Math.round(FALL_STEPS_PER_TICK * ageTicks) : 0;
}

function wrapYawDelta(d: number): number {
  const m = ((d % YAW_STEPS) + YAW_STEPS) % YAW_STEPS;
  return m >= YAW_STEPS / 2 ? m - YAW_STEPS : m;
}

/** Writes the character section; `ageTicks` is frame tick − baseline tick (0 for a full snapshot). */
export function encodeCharacters(format: SnapshotFormat, enc: RangeEncoder, frame: QuantizedFrame, base: QuantizedFrame, diff: RowDiff, ageTicks: number): void {
  const m = encoderModels.fresh();
  const cur = frame.characters;
  const old = base.characters;
  const { removed, spawnedIds, spawnedIdx, changed, changedBase } = diff;
  m.lists.encode(enc, removed, 0);
  m.lists.encode(enc, spawnedIds, 1);
  m.lists.encode(enc, changed, 2);
  const pb = format.positionBits;
  for (const idx of spawnedIdx) {
    const a = idx * CHARACTER_Q_STRIDE;
    m.bodyId.encode(enc, cur[a]);
    for (let f = 0; f < 3; f++) enc.encodeDirect(cur[a + 1 + f], pb[f]);
    for (let f = 4; f < 7; f++) enc.encodeDirect(cur[a + f] + VELOCITY_LIMIT, 16);
    enc.encodeDirect(cur[a + 7], 16);
    enc.encodeDirect(cur[a + 8] + PITCH_LIMIT, 16);
    enc.encodeDirect(cur[a + 9], 2);
    enc.encodeDirect(cur[a + 10], 8);
  }
  for (let c = 0; c < changed.length; c++) {
    const a = changed[c] * CHARACTER_Q_STRIDE;
    const b = changedBase[c] * CHARACTER_Q_STRIDE;
    const flag = (group: number, differs: boolean): boolean => {
      enc.encodeBit(m.changedFlags, group, differs ? 1 : 0);
      return differs;
    };
    if (flag(0, cur[a] !== old[b])) m.bodyId.encode(enc, cur[a]);
    // Ground state, then velocity, then position: each prediction uses what came before.
    if (flag(5, cur[a + 9] !== old[b + 9])) enc.encodeDirect(cur[a + 9], 2);
    const fall = predictedFall(old[b + 9], cur[a + 9], ageTicks);
    const dv = [cur[a + 4] - old[b + 4], cur[a + 5] - old[b + 5] - fall, cur[a + 6] - old[b + 6]];
    if (flag(2, dv[0] !== 0 || dv[1] !== 0 || dv[2] !== 0)) for (let f = 0; f < 3; f++) m.velocity.encode(enc, dv[f], f === 1 ? 1 : 0);
    const grounded = old[b + 9] === ON_GROUND && cur[a + 9] === ON_GROUND;
    const err = [0, 0, 0];
    for (let f = 0; f < 3; f++) err[f] = cur[a + 1 + f] - old[b + 1 + f] - predictedSteps(format, f, old[b + 4 + f], cur[a + 4 + f], ageTicks, grounded);
    if (flag(1, err[0] !== 0 || err[1] !== 0 || err[2] !== 0)) for (let f = 0; f < 3; f++) m.position.encode(enc, err[f], f === 1 ? 1 : 0);
    if (flag(3, cur[a + 7] !== old[b + 7])) m.angle.encode(enc, wrapYawDelta(cur[a + 7] - old[b + 7]), 0);
    if (flag(4, cur[a + 8] !== old[b + 8])) m.angle.encode(enc, cur[a + 8] - old[b + 8], 1);
    if (flag(6, cur[a + 10] !== old[b + 10])) enc.encodeDirect(cur[a + 10], 8);
  }
}

/** Reads the character section against the baseline; throws a clear Error on corrupt values. */
export function decodeCharacters(format: SnapshotFormat, dec: RangeDecoder, tick: number, base: QuantizedFrame, maxSpawns: number, ageTicks: number): { playerIds: Uint32Array; characters: Int32Array } {
  const m = decoderModels.fresh();
  const baseCount = base.playerIds.length;
  const removed = m.lists.decode(dec, 0, baseCount, baseCount - 1, 'removed characters', tick);
  const spawned = m.lists.decode(dec, 1, maxSpawns, 0x7fff_ffff, 'spawned characters', tick);
  const count = baseCount - removed.length + spawned.length;
  const changed = m.lists.decode(dec, 2, count, count - 1, 'changed characters', tick);
  const { ids, fromBase } = mergeIds(base.playerIds, removed, spawned, 'character', tick);
  const out = keptRows(fromBase, base.characters, CHARACTER_Q_STRIDE, removed.length === 0 && spawned.length === 0);
  const pb = format.positionBits;
  const steps = format.positionSteps;
  for (let i = 0; i < count; i++) {
    if (fromBase[i] >= 0) continue;
    const a = i * CHARACTER_Q_STRIDE;
    out[a] = m.bodyId.decode(dec);
    for (let f = 0; f < 3; f++) out[a + 1 + f] = checkRange(dec.decodeDirect(pb[f]), 0, steps[f], 'character position', tick);
    for (let f = 4; f < 7; f++) out[a + f] = checkRange(dec.decodeDirect(16) - VELOCITY_LIMIT, -VELOCITY_LIMIT, VELOCITY_LIMIT, 'character velocity', tick);
    out[a + 7] = dec.decodeDirect(16);
    out[a + 8] = checkRange(dec.decodeDirect(16) - PITCH_LIMIT, -PITCH_LIMIT, PITCH_LIMIT, 'character pitch', tick);
    out[a + 9] = dec.decodeDirect(2);
    out[a + 10] = dec.decodeDirect(8);
  }
  for (const idx of changed) {
    if (fromBase[idx] < 0) throw new Error(`snapshot ${tick} corrupt: changed character index ${idx} is not a kept character`);
    const a = idx * CHARACTER_Q_STRIDE;
    const flag = (group: number): boolean => dec.decodeBit(m.changedFlags, group) === 1;
    if (flag(0)) out[a] = m.bodyId.decode(dec);
    const ground0 = out[a + 9];
    if (flag(5)) out[a + 9] = dec.decodeDirect(2);
    const fall = predictedFall(ground0, out[a + 9], ageTicks);
    const v0 = [out[a + 4], out[a + 5], out[a + 6]];
    const accelerated = flag(2);
    for (let f = 0; f < 3; f++) {
      const d = (accelerated ? m.velocity.decode(dec, f === 1 ? 1 : 0) : 0) + (f === 1 ? fall : 0);
      out[a + 4 + f] = checkRange(out[a + 4 + f] + d, -VELOCITY_LIMIT, VELOCITY_LIMIT, 'character velocity', tick);
    }
    const grounded = ground0 === ON_GROUND && out[a + 9] === ON_GROUND;
    const moved = flag(1);
    for (let f = 0; f < 3; f++) {
      const e = moved ? m.position.decode(dec, f === 1 ? 1 : 0) : 0;
      out[a + 1 + f] = checkRange(out[a + 1 + f] + predictedSteps(format, f, v0[f], out[a + 4 + f], ageTicks, grounded) + e, 0, steps[f], 'character position', tick);
    }
    if (flag(3)) out[a + 7] = (((out[a + 7] + m.angle.decode(dec, 0)) % YAW_STEPS) + YAW_STEPS) % YAW_STEPS;
    if (flag(4)) out[a + 8] = checkRange(out[a + 8] + m.angle.decode(dec, 1), -PITCH_LIMIT, PITCH_LIMIT, 'character pitch', tick);
    if (flag(6)) out[a + 10] = dec.decodeDirect(8);
  }
  return { playerIds: ids, characters: out };
}
