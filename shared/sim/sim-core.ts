// The simulation's mutable state in one plain object (the tick, checkpoints and the hash all work on it), plus the
// body bookkeeping every phase shares: create a described body, remove one, map sensor events to SimEvents.
import { IDENTITY_QUAT, type PhysicsWorld, type QuatLike, type SensorEvent, type ShapeSpec, type Vec3Like } from '../physics/index.ts';
import type { BodyKind, BodyRecord, BodyRegistry } from './body-registry.ts';
import { makeRecord } from './body-registry.ts';
import type { BulletList } from './bullets.ts';
import type { GameInputField } from './game-input.ts';
import type { GameMessageKind } from './game-messages.ts';
import type { GameStateStore } from './game-state.ts';
import type { PlayerTable, ResolvedPlayerRules } from './players.ts';
import type { Prng } from './prng.ts';
import type { ParamValues, ScenarioContext, ScenarioDefinition, ScenarioInstance, SpawnOptions } from './scenario.ts';
import type { PlayerCommand, SimEvent } from './types.ts';

/** Everything a Simulation owns. Only shared/sim touches this object. */
export interface SimCore extends SimBase {
  instance: ScenarioInstance;
  ctx: ScenarioContext;
}

/** A simulation's state before its scenario is built: everything but the scenario's context and instance. */
export interface SimBase {
  readonly def: ScenarioDefinition;
  readonly params: ParamValues;
  readonly seed: number | string;
  readonly world: PhysicsWorld;
  readonly rng: Prng;
  readonly rules: ResolvedPlayerRules;
  /** The scenario's game input fields, sorted by name (empty when it declares none). */
  readonly gameInputFields: readonly GameInputField[];
  /** The scenario's game message kinds, sorted by name. */
  readonly gameMessageKinds: readonly GameMessageKind[];
  /** The scenario's replicated game state. */
  readonly gameState: GameStateStore;
  readonly registry: BodyRegistry;
  readonly players: PlayerTable;
  readonly bullets: BulletList;
  /** Records of the bodies the scenario built (tick 0 scene), kept for the whole session. */
  readonly buildRecords: Map<number, BodyRecord>;
  /** Ticks applied so far; the next record must carry this tick number. */
  tick: number;
  /** 'building' while the scenario builds, 'tick' inside step(), 'idle' between ticks. */
  phase: 'building' | 'tick' | 'idle';
  /** The tick being simulated (ScenarioContext.tick). */
  currentTick: number;
  /** Events of the tick in progress, in the order they happen. */
  tickEvents: SimEvent[];
  /** The commands applied this tick (ScenarioContext.inputs). */
  tickInputs: PlayerCommand[];
  /** Sensor transitions raised after the tick's last drain (bodies removed by onEvents): delivered next tick. */
  carriedSensor: SensorEvent[];
  /** Character bodies removed this tick, with their player ids (their sensor exits still name the player). */
  departed: Map<number, number>;
  /** Set when a scenario hook threw mid-tick: the state is half-updated until a checkpoint is restored. */
  failure: Error | null;
}

/** Checks a spawn's render options before any Jolt object exists. */
function checkSpawnOptions(opts: SpawnOptions, what: string): void {
  if (opts === null || typeof opts !== 'object') throw new Error(`${what}: options must be an object`);
  const c = opts.color;
  if (c !== undefined && (!Array.isArray(c) || c.length !== 3 || c.some((v) => typeof v !== 'number' || !Number.isFinite(v) || v < 0 || v > 1))) {
    throw new Error(`${what}: color must be three numbers in [0, 1]`);
  }
  if (opts.hidden !== undefined && typeof opts.hidden !== 'boolean') throw new Error(`${what}: hidden must be a boolean`);
}

/** Creates a body through the world and records it; `at` recreates a saved body under its ids. */
export function createBody(core: SimBase, kind: BodyKind, spec: ShapeSpec, position: Vec3Like, rotation: QuatLike | null, opts: SpawnOptions, at?: { id: number; joltId: number }): BodyRecord {
  const what = `${kind} ${spec?.kind ?? 'shape'}${opts?.name ? ` "${opts.name}"` : ''}`;
  checkSpawnOptions(opts, what);
  const handle = core.world.addShape(spec, position, rotation, opts, at);
  const record = makeRecord(kind, handle, spec, position, rotation ?? IDENTITY_QUAT, opts);
  core.registry.add(record);
  return record;
}

/** Re-adds a saved record's body under its saved ids (checkpoint restore); the record is reused as is. */
export function recreateBody(core: SimCore, record: BodyRecord): void {
  core.world.addShape(record.spec, record.position, record.rotation, record.opts, { id: record.id, joltId: record.joltId });
  core.registry.add(record);
}

/** Removes a non-character body from the world and the registry. */
export function destroyBody(core: SimBase, id: number): void {
  core.world.removeBody(id);
  core.registry.delete(id);
}

/** Throws when a scenario added or removed bodies behind the simulation's back (through ctx.world). */
export function assertRegistryInSync(core: SimBase, hook: string): void {
  if (core.world.bodyCount !== core.registry.size) {
    throw new Error(
      `scenario ${core.def.name}: ${hook} changed bodies through ctx.world directly (${core.world.bodyCount} in the world, ` +
        `${core.registry.size} known); use ctx.spawn and ctx.remove so bodies are described, hashed and checkpointed`,
    );
  }
}

/** Maps the physics layer's sensor transitions to SimEvents (player id when the other body is a character). */
export function sensorSimEvents(core: SimCore, tick: number, raw: readonly SensorEvent[]): SimEvent[] {
  const out: SimEvent[] = [];
  for (const e of raw) {
    const rec = core.registry.get(e.otherId);
    const playerId = rec?.kind === 'character' ? rec.descriptor.playerId : core.departed.get(e.otherId);
    const type = e.kind === 'enter' ? ('sensorEnter' as const) : ('sensorExit' as const);
    out.push(playerId === undefined ? { type, tick, sensorId: e.sensorId, bodyId: e.otherId } : { type, tick, sensorId: e.sensorId, bodyId: e.otherId, playerId });
  }
  return out;
}
