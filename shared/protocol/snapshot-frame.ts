// The quantized world state one snapshot describes (QuantizedFrame), built once per tick from the simulation's bulk
// read and shared by every client's encoder; and its float view (SnapshotView) for interpolation and rendering.
import { BODY_STATE_STRIDE, BodyFlag } from '../physics-data/body-state.ts';
import type { CharacterState } from '../sim/types.ts';
import type { FrameLease, QuantizedFramePool } from './frame-pool.ts';
import {
  GROUND_STATES,
  dequantizeAxis,
  dequantizePitch,
  dequantizeRotation,
  dequantizeVelocity,
  dequantizeYaw,
  groundStateCode,
  quantizeAxis,
  quantizePitch,
  quantizeRotation,
  quantizeVelocity,
  quantizeYaw,
  type SnapshotFormat,
} from './quantization.ts';

/** Integers per body in QuantizedFrame.bodies: px, py, pz, rotation index, rotation a, b, c, at-rest (0/1). */
export const BODY_Q_STRIDE = 8;
/** Integers per character: bodyId, px, py, pz, vx, vy, vz, yaw, pitch, ground state, buttons. */
export const CHARACTER_Q_STRIDE = 11;
/** Offsets inside one body's record. */
export const BodyQ = { Px: 0, Py: 1, Pz: 2, RotIndex: 3, RotA: 4, RotB: 5, RotC: 6, AtRest: 7 } as const;
/** Offsets inside one character's record. */
export const CharacterQ = { BodyId: 0, Px: 1, Py: 2, Pz: 3, Vx: 4, Vy: 5, Vz: 6, Yaw: 7, Pitch: 8, Ground: 9, Buttons: 10 } as const;

/** The exact integer state a snapshot carries; the decoder reproduces it bit for bit. Immutable once built. */
export interface QuantizedFrame {
  readonly tick: number;
  /** Body ids, strictly ascending. */
  readonly bodyIds: Uint32Array;
  /** BODY_Q_STRIDE integers per body, in bodyIds order. */
  readonly bodies: Int32Array;
  /** Player ids of the characters, strictly ascending. */
  readonly playerIds: Uint32Array;
  /** CHARACTER_Q_STRIDE integers per character, in playerIds order. */
  readonly characters: Int32Array;
  /** Set when the arrays come from a QuantizedFramePool: whoever keeps the frame retains it (frame-pool.ts). */
  readonly lease?: FrameLease;
}

/** The simulation's bulk read (`readBodyStates()`): ids ascending, 13 floats per body, BodyFlag bits. */
export interface BodyStatesRead {
  count: number;
  ids: ArrayLike<number>;
  states: ArrayLike<number>;
  flags: ArrayLike<number>;
}

/** A snapshot as floats, for interpolation and rendering. */
export interface SnapshotView {
  tick: number;
  /** Body ids, ascending. */
  ids: Uint32Array;
  /** x, y, z per body (m). */
  positions: Float32Array;
  /** x, y, z, w per body (unit quaternion). */
  rotations: Float32Array;
  /** 1 where the body is asleep (not active) on the server. */
  atRest: Uint8Array;
  /** Characters by ascending player id. */
  characters: CharacterState[];
}

/** Options of quantizeFrame. */
export interface QuantizeFrameOptions {
  /** Static bodies are normally sent once in the welcome; return true for a static body that snapshots must carry. */
  includeStatic?: (bodyId: number) => boolean;
  /**
   * The previous frame quantized in the SAME format and the read it came from: bodies whose pose floats are equal
   * reuse its integers instead of quantizing again (bodies at rest cost a comparison). Same result either way.
   */
  previous?: { read: BodyStatesRead; frame: QuantizedFrame };
  /** Where the frame's arrays come from (reused buffers; the frame then carries a lease its holders retain). */
  pool?: QuantizedFramePool;
}

/**
 * Quantizes the world for one tick: every non-static body (dynamic, kinematic, character capsules, moving sensors)
 * plus the characters. Throws on unsorted ids or ids ≥ 2^31 (the wire's limit).
 */
export function quantizeFrame(format: SnapshotFormat, tick: number, read: BodyStatesRead, characters: readonly CharacterState[], opts: QuantizeFrameOptions = {}): QuantizedFrame {
  if (!Number.isInteger(tick) || tick < 0 || tick > 0xffff_ffff) throw new Error(`quantizeFrame: tick must be a uint32, got ${tick}`);
  const n = read.count;
  const include = opts.includeStatic;
  let kept = 0;
  for (let i = 0; i < n; i++) {
    if ((read.flags[i] & BodyFlag.Static) === 0 || (include !== undefined && include(read.ids[i]))) kept++;
  }
  const states = read.states;
  const minX = format.bounds.min.x;
  const minY = format.bounds.min.y;
  const minZ = format.bounds.min.z;
  const [stepX, stepY, stepZ] = format.positionStepMetres;
  const [stepsX, stepsY, stepsZ] = format.positionSteps;
  const sorted = characters.length > 1 ? [...characters].sort((a, b) => a.playerId - b.playerId) : characters;
  const pooled = opts.pool?.take(kept, sorted.length);
  const bodyIds = pooled?.bodyIds ?? new Uint32Array(kept);
  const bodies = pooled?.bodies ?? new Int32Array(kept * BODY_Q_STRIDE);
  const prevRead = opts.previous?.read;
  const prevFrame = opts.previous?.frame;
  let pi = 0;
  let pj = 0;
  let j = 0;
  let prev = -1;
  for (let i = 0; i < n; i++) {
    const id = read.ids[i];
    if (!(id > prev)) throw new Error(`quantizeFrame: body ids must be strictly ascending (id ${id} after ${prev})`);
    if (id > 0x7fff_ffff) throw new Error(`quantizeFrame: body id ${id} exceeds 2^31-1`);
    prev = id;
    const flags = read.flags[i];
    if ((flags & BodyFlag.Static) !== 0 && !(include !== undefined && include(id))) continue;
    const s = i * BODY_STATE_STRIDE;
    const o = j * BODY_Q_STRIDE;
    bodyIds[j] = id;
    let reused = false;
    if (prevRead !== undefined && prevFrame !== undefined) {
      while (pi < prevRead.count && prevRead.ids[pi] < id) pi++;
      const ps = pi * BODY_STATE_STRIDE;
      const ps0 = prevRead.states;
      if (pi < prevRead.count && prevRead.ids[pi] === id && ps0[ps] === states[s] && ps0[ps + 1] === states[s + 1] && ps0[ps + 2] === states[s + 2] && ps0[ps + 3] === states[s + 3] && ps0[ps + 4] === states[s + 4] && ps0[ps + 5] === states[s + 5] && ps0[ps + 6] === states[s + 6]) {
        const ids = prevFrame.bodyIds;
        while (pj < ids.length && ids[pj] < id) pj++;
        if (pj < ids.length && ids[pj] === id) {
          const po = pj * BODY_Q_STRIDE;
          for (let f = 0; f < 7; f++) bodies[o + f] = prevFrame.bodies[po + f];
          reused = true;
        }
      }
    }
    if (!reused) {
      bodies[o] = gridIndex(states[s], minX, stepX, stepsX);
      bodies[o + 1] = gridIndex(states[s + 1], minY, stepY, stepsY);
      bodies[o + 2] = gridIndex(states[s + 2], minZ, stepZ, stepsZ);
      quantizeRotation(format, states[s + 3], states[s + 4], states[s + 5], states[s + 6], bodies, o + 3);
    }
    bodies[o + 7] = (flags & BodyFlag.Active) === 0 ? 1 : 0;
    j++;
  }
  const playerIds = pooled?.playerIds ?? new Uint32Array(sorted.length);
  const chars = pooled?.characters ?? new Int32Array(sorted.length * CHARACTER_Q_STRIDE);
  for (let i = 0; i < sorted.length; i++) {
    const c = sorted[i];
    if (!Number.isInteger(c.playerId) || c.playerId < 0 || c.playerId > 0x7fff_ffff) throw new Error(`quantizeFrame: bad player id ${c.playerId}`);
    if (i > 0 && c.playerId === sorted[i - 1].playerId) throw new Error(`quantizeFrame: player ${c.playerId} appears twice`);
    if (!Number.isInteger(c.bodyId) || c.bodyId < 0 || c.bodyId > 0x7fff_ffff) throw new Error(`quantizeFrame: bad body id ${c.bodyId} for player ${c.playerId}`);
    playerIds[i] = c.playerId;
    const o = i * CHARACTER_Q_STRIDE;
    chars[o] = c.bodyId;
    chars[o + 1] = quantizeAxis(format, 0, c.position.x);
    chars[o + 2] = quantizeAxis(format, 1, c.position.y);
    chars[o + 3] = quantizeAxis(format, 2, c.position.z);
    chars[o + 4] = quantizeVelocity(c.velocity.x);
    chars[o + 5] = quantizeVelocity(c.velocity.y);
    chars[o + 6] = quantizeVelocity(c.velocity.z);
    chars[o + 7] = quantizeYaw(c.yaw);
    chars[o + 8] = quantizePitch(c.pitch);
    chars[o + 9] = groundStateCode(c.groundState);
    chars[o + 10] = (c.buttons >>> 0) & 0xff;
  }
  return pooled === undefined ? { tick, bodyIds, bodies, playerIds, characters: chars } : { tick, bodyIds, bodies, playerIds, characters: chars, lease: pooled.lease };
}

/** quantizeAxis with the axis constants hoisted (the per-body hot path). */
function gridIndex(metres: number, min: number, step: number, steps: number): number {
  const q = Math.round((metres - min) / step);
  if (!(q >= 0)) return 0;
  return q > steps ? steps : q;
}

/** An empty frame (the implicit baseline of a full snapshot). */
export function emptyFrame(tick = 0): QuantizedFrame {
  return { tick, bodyIds: new Uint32Array(0), bodies: new Int32Array(0), playerIds: new Uint32Array(0), characters: new Int32Array(0) };
}

/** Whether two frames hold identical integers (ticks included). */
export function framesEqual(a: QuantizedFrame, b: QuantizedFrame): boolean {
  return a.tick === b.tick && sameInts(a.bodyIds, b.bodyIds) && sameInts(a.bodies, b.bodies) && sameInts(a.playerIds, b.playerIds) && sameInts(a.characters, b.characters);
}

function sameInts(a: ArrayLike<number>, b: ArrayLike<number>): boolean {
  if (a.length !== b.length) return false;
  for (let i = 0; i < a.length; i++) if (a[i] !== b[i]) return false;
  return true;
}

/** Dequantizes one character record. */
export function dequantizeCharacter(format: SnapshotFormat, playerId: number, chars: Int32Array, index: number): CharacterState {
  const o = index * CHARACTER_Q_STRIDE;
  return {
    playerId,
    bodyId: chars[o],
    position: { x: dequantizeAxis(format, 0, chars[o + 1]), y: dequantizeAxis(format, 1, chars[o + 2]), z: dequantizeAxis(format, 2, chars[o + 3]) },
    velocity: { x: dequantizeVelocity(chars[o + 4]), y: dequantizeVelocity(chars[o + 5]), z: dequantizeVelocity(chars[o + 6]) },
    yaw: dequantizeYaw(chars[o + 7]),
    pitch: dequantizePitch(chars[o + 8]),
    groundState: GROUND_STATES[chars[o + 9] & 3],
    buttons: chars[o + 10],
  };
}

/** Float view of a frame: positions on the grid, unit quaternions, at-rest flags, characters. */
export function dequantizeFrame(format: SnapshotFormat, frame: QuantizedFrame): SnapshotView {
  const n = frame.bodyIds.length;
  const positions = new Float32Array(n * 3);
  const rotations = new Float32Array(n * 4);
  const atRest = new Uint8Array(n);
  const b = frame.bodies;
  for (let i = 0; i < n; i++) {
    const o = i * BODY_Q_STRIDE;
    positions[i * 3] = dequantizeAxis(format, 0, b[o]);
    positions[i * 3 + 1] = dequantizeAxis(format, 1, b[o + 1]);
    positions[i * 3 + 2] = dequantizeAxis(format, 2, b[o + 2]);
    dequantizeRotation(format, b[o + 3], b[o + 4], b[o + 5], b[o + 6], rotations, i * 4);
    atRest[i] = b[o + 7];
  }
  const characters: CharacterState[] = [];
  for (let i = 0; i < frame.playerIds.length; i++) characters.push(dequantizeCharacter(format, frame.playerIds[i], frame.characters, i));
  return { tick: frame.tick, ids: frame.bodyIds.slice(), positions, rotations, atRest, characters };
}
