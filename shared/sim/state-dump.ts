// What the state hash covers, as data: a StateDump of a simulation (bodies' raw float bits in id order, characters,
// players, PRNG, bullets, scenario state), its 64-bit hash, and the first difference between two dumps.
import { BODY_STATE_STRIDE, type PhysicsWorld } from '../physics/index.ts';
import { worldInternals } from '../physics/internal.ts';
import type { Bullet } from './bullets.ts';
import type { InputCommand } from './input.ts';
import type { SimCore } from './sim-core.ts';
import { Hasher64 } from './state-hash.ts';

/** The world's bulk body read (ids ascending, 13 floats per body, BodyFlag bits). */
type BodyStates = ReturnType<PhysicsWorld['readBodyStates']>;

const GROUND_CODES = { ground: 0, steep: 1, air: 2, unsupported: 3 } as const;

/** One player's hashed state. */
export interface PlayerDump {
  playerId: number;
  name: string;
  joinIndex: number;
  bodyId: number;
  input: InputCommand;
  nextFireTick: number;
  /** Feet position (float32 values), velocity and pending jump speed (float64 values). */
  position: [number, number, number];
  velocity: [number, number, number];
  groundState: number;
  pendingJumpSpeed: number;
}

/** Everything the state hash covers, copied out of a simulation after a tick. */
export interface StateDump {
  tick: number;
  prng: number[];
  nextBodyId: number;
  joinCount: number;
  /** Body ids ascending, 13 float32 per body (position, rotation, linear and angular velocity), BodyFlag bits. */
  ids: Uint32Array;
  states: Float32Array;
  flags: Uint8Array;
  players: PlayerDump[];
  bullets: Bullet[];
  scenarioState: number[];
  /** Game state values in field order (empty when the scenario declares none). */
  gameState: (number | string)[];
  /** Sensor transitions carried into the next tick, as (kind 0 exit / 1 enter, sensor id, other id) triples. */
  carriedSensor: number[];
  /** Open sensor overlaps as (sensor id, other id, count) triples. */
  overlaps: number[];
}

/**
 * The hashed state of a simulation core. With `copy` false the body arrays are views into the world's reused
 * read buffers (valid until the next read: enough to hash at once without copying). `bodies`: this tick's bulk read
 * when the caller already has it (saves reading every body again).
 */
export function dumpState(core: SimCore, copy = true, bodies?: BodyStates): StateDump {
  const b = bodies ?? core.world.readBodyStates();
  const rows = worldInternals(core.world).sensorHub.exportOverlaps();
  const overlaps: number[] = [];
  for (let i = 0; i + 4 < rows.length; i += 5) overlaps.push(rows[i + 2], rows[i + 3], rows[i + 4]);
  return {
    tick: core.tick,
    prng: core.rng.getState(),
    nextBodyId: core.world.nextId,
    joinCount: core.players.joinCount,
    ids: copy ? b.ids.slice() : b.ids,
    states: copy ? b.states.slice() : b.states,
    flags: copy ? b.flags.slice() : b.flags,
    players: core.players.inOrder().map((p) => {
      const c = p.controller;
      const pos = c.position;
      return {
        playerId: p.playerId,
        name: p.name,
        joinIndex: p.joinIndex,
        bodyId: p.bodyId,
        input: { ...p.input },
        nextFireTick: p.nextFireTick,
        position: [pos.x, pos.y, pos.z],
        velocity: [c.velocity.x, c.velocity.y, c.velocity.z],
        groundState: GROUND_CODES[c.groundState],
        pendingJumpSpeed: c.pendingJumpSpeed,
      };
    }),
    bullets: core.bullets.snapshot(),
    scenarioState: core.instance.saveState ? core.instance.saveState().slice() : [],
    gameState: core.gameState.list(),
    carriedSensor: core.carriedSensor.flatMap((e) => [e.kind === 'enter' ? 1 : 0, e.sensorId, e.otherId]),
    overlaps,
  };
}

// A player's identity and current input, as both hashes (of a dump, and streamed from the simulation) word them.
function hashPlayerInput(h: Hasher64, p: Pick<PlayerDump, 'playerId' | 'joinIndex' | 'bodyId' | 'name' | 'input' | 'nextFireTick'>): void {
  h.word(p.playerId).word(p.joinIndex).word(p.bodyId).string(p.name);
  const i = p.input;
  h.word(i.moveX).word(i.moveZ).word(i.yaw).word(i.pitch).word(i.buttons).word(p.nextFireTick);
  // Game input only where a scenario declares it, so scenarios without it hash exactly as before.
  if (i.game !== undefined && i.game.length > 0) {
    h.word(i.game.length);
    for (const v of i.game) h.word(v);
  }
}

function hashPlayer(h: Hasher64, p: PlayerDump): void {
  hashPlayerInput(h, p);
  h.f32Bits(p.position[0]).f32Bits(p.position[1]).f32Bits(p.position[2]);
  h.f64Bits(p.velocity[0]).f64Bits(p.velocity[1]).f64Bits(p.velocity[2]);
  h.word(p.groundState).f64Bits(p.pendingJumpSpeed);
}

/** The state hash of a dump: 16 lowercase hex characters (see docs/simulation.md for the exact word order). */
export function hashDump(d: StateDump): string {
  const h = new Hasher64();
  h.word(d.tick);
  for (const w of d.prng) h.word(w);
  h.word(d.nextBodyId).word(d.joinCount);
  const n = d.ids.length;
  h.word(n).words(d.ids);
  h.words(new Uint32Array(d.states.buffer, d.states.byteOffset, n * BODY_STATE_STRIDE));
  for (let i = 0; i < n; i += 4) h.word(d.flags[i] | (d.flags[i + 1] << 8) | (d.flags[i + 2] << 16) | (d.flags[i + 3] << 24));
  h.word(d.players.length);
  for (const p of d.players) hashPlayer(h, p);
  h.word(d.bullets.length);
  for (const b of d.bullets) h.word(b.bodyId).word(b.ownerId).word(b.expireTick);
  h.word(d.scenarioState.length);
  const scenario = Float64Array.from(d.scenarioState); // each value as two words, low then high (little-endian)
  h.words(new Uint32Array(scenario.buffer));
  // Game state only where a scenario declares it, so scenarios without it hash exactly as before.
  if (d.gameState.length > 0) {
    h.word(d.gameState.length);
    for (const v of d.gameState) {
      if (typeof v === 'number') h.word(0).f64Bits(v);
      else h.word(1).string(v);
    }
  }
  h.word(d.carriedSensor.length);
  for (const v of d.carriedSensor) h.word(v);
  h.word(d.overlaps.length);
  for (const v of d.overlaps) h.word(v);
  return h.hex();
}

/** hashState's hasher, reused: the hash runs to completion before anything else can use it. */
const streamHasher = new Hasher64();
/** hashState's scenario values as float64s, reused (grown on demand). */
let scenarioValues = new Float64Array(64);

/**
 * The scenario state's words (each value's float64 bits, low word first) in a reused buffer, valid until the next
 * call: one bulk words() instead of two word() calls per value (shape-rain 1000 saves 2001 values).
 */
function scenarioWords(values: readonly number[]): Uint32Array {
  const n = values.length;
  if (scenarioValues.length < n) scenarioValues = new Float64Array(Math.max(n, scenarioValues.length * 2));
  for (let i = 0; i < n; i++) scenarioValues[i] = values[i];
  return new Uint32Array(scenarioValues.buffer, 0, n * 2);
}

/**
 * The state hash of a simulation core straight from its state: the very words hashDump(dumpState(core)) hashes, in
 * the same order, without building the dump (no copies; `bodies` is this tick's bulk read).
 */
export function hashState(core: SimCore, bodies: BodyStates): string {
  const h = streamHasher.reset();
  h.word(core.tick);
  const [s0, s1, s2, s3] = core.rng.getState();
  h.word(s0).word(s1).word(s2).word(s3);
  h.word(core.world.nextId).word(core.players.joinCount);
  const n = bodies.ids.length;
  const { ids, states, flags } = bodies;
  h.word(n).words(ids);
  h.words(new Uint32Array(states.buffer, states.byteOffset, n * BODY_STATE_STRIDE));
  for (let i = 0; i < n; i += 4) h.word(flags[i] | (flags[i + 1] << 8) | (flags[i + 2] << 16) | (flags[i + 3] << 24));
  const players = core.players.inOrder();
  h.word(players.length);
  for (const p of players) {
    const c = p.controller;
    const pos = c.position;
    hashPlayerInput(h, p);
    h.f32Bits(pos.x).f32Bits(pos.y).f32Bits(pos.z);
    h.f64Bits(c.velocity.x).f64Bits(c.velocity.y).f64Bits(c.velocity.z);
    h.word(GROUND_CODES[c.groundState]).f64Bits(c.pendingJumpSpeed);
  }
  const bullets = core.bullets.live();
  h.word(bullets.length);
  for (const b of bullets) h.word(b.bodyId).word(b.ownerId).word(b.expireTick);
  const scenario = core.instance.saveState ? core.instance.saveState() : [];
  h.word(scenario.length);
  h.words(scenarioWords(scenario)); // low word, then high: as hashDump's little-endian Float64Array view
  const game = core.gameState.list();
  if (game.length > 0) {
    h.word(game.length);
    for (const v of game) {
      if (typeof v === 'number') h.word(0).f64Bits(v);
      else h.word(1).string(v);
    }
  }
  h.word(core.carriedSensor.length * 3);
  for (const e of core.carriedSensor) h.word(e.kind === 'enter' ? 1 : 0).word(e.sensorId).word(e.otherId);
  const rows = worldInternals(core.world).sensorHub.exportOverlaps();
  const overlapRows = Math.floor(rows.length / 5);
  h.word(overlapRows * 3);
  for (let r = 0; r < overlapRows; r++) h.word(rows[r * 5 + 2]).word(rows[r * 5 + 3]).word(rows[r * 5 + 4]);
  return h.hex();
}

/** Where two dumps first differ: null when identical. Bodies are compared in id order, field by field. */
export interface Divergence {
  /** Which part differs first, in hash order. */
  part: 'tick' | 'prng' | 'ids' | 'body' | 'players' | 'bullets' | 'scenario' | 'sensors';
  /** The first differing body (part 'body' or 'ids'). */
  bodyId?: number;
  /** The first differing player (part 'players'). */
  playerId?: number;
  /** A readable description. */
  detail: string;
}

const FIELDS = ['position', 'rotation', 'linearVelocity', 'angularVelocity'] as const;
const FIELD_OF = [0, 0, 0, 1, 1, 1, 1, 2, 2, 2, 3, 3, 3];

function sameNumbers(a: readonly number[], b: readonly number[]): boolean {
  return a.length === b.length && a.every((v, i) => Object.is(v, b[i]));
}

/** Compares two dumps and names the first difference (first differing body id for body state). */
export function firstDivergence(a: StateDump, b: StateDump): Divergence | null {
  if (a.tick !== b.tick) return { part: 'tick', detail: `tick ${a.tick} vs ${b.tick}` };
  if (!sameNumbers(a.prng, b.prng) || a.nextBodyId !== b.nextBodyId || a.joinCount !== b.joinCount) {
    return { part: 'prng', detail: `PRNG/id counters differ (next body id ${a.nextBodyId} vs ${b.nextBodyId}, joins ${a.joinCount} vs ${b.joinCount})` };
  }
  const ua = new Uint32Array(a.states.buffer, a.states.byteOffset, a.ids.length * BODY_STATE_STRIDE);
  const ub = new Uint32Array(b.states.buffer, b.states.byteOffset, b.ids.length * BODY_STATE_STRIDE);
  let i = 0;
  let j = 0;
  while (i < a.ids.length || j < b.ids.length) {
    const ia = i < a.ids.length ? a.ids[i] : Infinity;
    const ib = j < b.ids.length ? b.ids[j] : Infinity;
    if (ia !== ib) {
      const id = Math.min(ia, ib);
      return { part: 'ids', bodyId: id, detail: `body ${id} exists only in the ${ia < ib ? 'first' : 'second'} state` };
    }
    for (let k = 0; k < BODY_STATE_STRIDE; k++) {
      if (ua[i * BODY_STATE_STRIDE + k] !== ub[j * BODY_STATE_STRIDE + k]) {
        const field = FIELDS[FIELD_OF[k]];
        return { part: 'body', bodyId: ia, detail: `body ${ia} ${field} differs: ${a.states[i * BODY_STATE_STRIDE + k]} vs ${b.states[j * BODY_STATE_STRIDE + k]}` };
      }
    }
    if (a.flags[i] !== b.flags[j]) return { part: 'body', bodyId: ia, detail: `body ${ia} flags differ (${a.flags[i]} vs ${b.flags[j]}: sleeping/active)` };
    i++;
    j++;
  }
  const n = Math.max(a.players.length, b.players.length);
  for (let k = 0; k < n; k++) {
    const pa = a.players[k];
    const pb = b.players[k];
    if (!pa || !pb || JSON.stringify(pa) !== JSON.stringify(pb) || !sameNumbers(pa.velocity, pb.velocity)) {
      const id = pa && pb ? pa.playerId : (pa ?? pb)!.playerId;
      return { part: 'players', playerId: id, detail: `player ${id} differs` };
    }
  }
  if (JSON.stringify(a.bullets) !== JSON.stringify(b.bullets)) return { part: 'bullets', detail: 'bullet lists differ' };
  if (!sameNumbers(a.scenarioState, b.scenarioState)) return { part: 'scenario', detail: 'scenario state differs' };
  const ga = a.gameState ?? [];
  const gb = b.gameState ?? [];
  if (ga.length !== gb.length || ga.some((v, i) => !Object.is(v, gb[i]))) return { part: 'scenario', detail: 'game state differs' };
  if (!sameNumbers(a.carriedSensor, b.carriedSensor) || !sameNumbers(a.overlaps, b.overlaps)) return { part: 'sensors', detail: 'sensor overlaps differ' };
  return null;
}
