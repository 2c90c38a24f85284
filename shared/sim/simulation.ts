// Simulation: one deterministic session of a scenario — a PhysicsWorld, the seeded Prng, the 60 Hz tick counter,
// the player table, body descriptors and events — with state hashes, divergence reports and checkpoints.
import { PhysicsWorld, type PhysicsWorldOptions } from '../physics/index.ts';
import { worldInternals } from '../physics/internal.ts';
import { BodyRegistry } from './body-registry.ts';
import { BulletList } from './bullets.ts';
import { captureData, restoreCheckpoint, saveCheckpoint, type Checkpoint } from './checkpoint.ts';
import { decodeCheckpoint, encodeCheckpoint } from './checkpoint-codec.ts';
import { resolveGameInputFields, type GameInputField } from './game-input.ts';
import { resolveGameMessageKinds, type GameMessageKind } from './game-messages.ts';
import { GameStateStore, resolveGameStateFields, type GameStateField, type GameStateValue, type GameStateValues } from './game-state.ts';
import { PlayerTable, resolvePlayerRules } from './players.ts';
import { Prng } from './prng.ts';
import { makeScenarioContext } from './scenario-context.ts';
import { resolveParams, type ParamValues, type ScenarioDefinition, type ScenarioInstance } from './scenario.ts';
import { assertRegistryInSync, type SimBase, type SimCore } from './sim-core.ts';
import { dumpState, firstDivergence, hashState, type Divergence, type StateDump } from './state-dump.ts';
import { runTick } from './tick.ts';
import type { BodyDescriptor, CharacterState, SimEvent, TickInputRecord } from './types.ts';

/** The world's bulk body read (ids ascending, 13 floats per body, BodyFlag bits). */
type BodyStates = ReturnType<PhysicsWorld['readBodyStates']>;

/** Options of Simulation.create. */
export interface SimulationOptions {
  scenario: ScenarioDefinition;
  /** Scenario parameters (defaults fill the rest; unknown or out-of-range values throw). */
  params?: Readonly<Record<string, number>>;
  /** PRNG seed: a 32-bit integer or any string. Default 1. */
  seed?: number | string;
  /** How to load Jolt (wasmBinary / wasmUrl) and overrides of the scenario's world limits. */
  worldOptions?: PhysicsWorldOptions;
}

function checkScenario(def: ScenarioDefinition): void {
  if (!def || typeof def !== 'object') throw new Error('Simulation.create: scenario must be a ScenarioDefinition');
  if (typeof def.name !== 'string' || def.name === '') throw new Error('Simulation.create: scenario.name must be a non-empty string');
  if (typeof def.build !== 'function') throw new Error(`scenario ${def.name}: build must be a function`);
  const b = def.bounds;
  const ok = (v: unknown): boolean => typeof v === 'number' && Number.isFinite(v);
  if (!b || !b.min || !b.max || ![b.min.x, b.min.y, b.min.z, b.max.x, b.max.y, b.max.z].every(ok) || b.min.x >= b.max.x || b.min.y >= b.max.y || b.min.z >= b.max.z) {
    throw new Error(`scenario ${def.name}: bounds must be finite {min, max} with min < max on every axis`);
  }
}

function checkSeed(seed: unknown): number | string {
  if (typeof seed === 'string') return seed;
  if (typeof seed === 'number' && Number.isInteger(seed) && seed >= 0 && seed <= 0xffffffff) return seed;
  throw new Error(`Simulation.create: seed must be an integer in [0, 2^32) or a string, got ${String(seed)}`);
}

/** A deterministic simulation of one scenario. Create with `await Simulation.create(...)`; destroy() when done. */
export class Simulation {
  private readonly core: SimCore;
  private hashCache: { tick: number; hash: string } | null = null;
  // The world's bulk read for the current tick: the state hash and the snapshot both need it after a step, and the
  // world cannot change between steps (it is read-only outside step/restore, which drop this).
  private readCache: { tick: number; states: BodyStates } | null = null;
  private destroyed = false;

  private constructor(core: SimCore) {
    this.core = core;
  }

  /** Loads Jolt, builds the scenario's world and returns the simulation at tick 0. */
  static async create(opts: SimulationOptions): Promise<Simulation> {
    if (!opts || typeof opts !== 'object') throw new Error('Simulation.create: options {scenario, params?, seed?} required');
    const def = opts.scenario;
    checkScenario(def);
    const params: ParamValues = resolveParams(def, opts.params ?? {});
    const seed = checkSeed(opts.seed ?? 1);
    const rules = resolvePlayerRules(def.players, `scenario ${def.name}`);
    const gameInputFields = resolveGameInputFields(def.input, def.name);
    const gameState = new GameStateStore(resolveGameStateFields(def.state, def.name));
    const gameMessageKinds = resolveGameMessageKinds(def.messages, def.name);
    const world = await PhysicsWorld.create({ ...(def.world ?? {}), ...(opts.worldOptions ?? {}) });
    const base: SimBase = {
      def,
      params,
      seed,
      world,
      rng: new Prng(seed),
      rules,
      gameInputFields,
      gameState,
      gameMessageKinds,
      registry: new BodyRegistry(),
      players: new PlayerTable(),
      bullets: new BulletList(),
      buildRecords: new Map(),
      tick: 0,
      phase: 'building',
      currentTick: 0,
      tickEvents: [],
      tickInputs: [],
      carriedSensor: [],
      departed: new Map(),
      failure: null,
    };
    // The context works on `base`; once the scenario is built, the same object gains its context and instance.
    const ctx = makeScenarioContext(base);
    let instance: ScenarioInstance;
    try {
      instance = def.build(ctx);
      if (!instance || typeof instance.spawnPoint !== 'function') throw new Error('build() must return an instance with spawnPoint(n)');
      assertRegistryInSync(base, 'build');
    } catch (err) {
      world.destroy();
      throw new Error(`scenario ${def.name}: build failed: ${(err as Error).message}`, { cause: err });
    }
    const core: SimCore = Object.assign(base, { ctx, instance });
    for (const r of core.registry.all()) core.buildRecords.set(r.id, r);
    core.carriedSensor = worldInternals(world).sensorHub.drain();
    core.phase = 'idle';
    return new Simulation(core);
  }

  private live(): SimCore {
    if (this.destroyed) throw new Error('Simulation was destroyed');
    return this.core;
  }

  /** Ticks applied so far; the next record must carry this tick number. */
  get tick(): number {
    return this.core.tick;
  }

  /** Most players in the game at once (the scenario's players.maxPlayers): joins past it are rejected. */
  get maxPlayers(): number {
    return this.core.rules.maxPlayers;
  }

  /** The scenario's name. */
  get scenarioName(): string {
    return this.core.def.name;
  }

  /** The resolved parameters. */
  get params(): ParamValues {
    return this.core.params;
  }

  /** The seed the PRNG started from. */
  get seed(): number | string {
    return this.core.seed;
  }

  /** The scenario's game input fields, sorted by name: the order of InputCommand.game. */
  get gameInputFields(): readonly GameInputField[] {
    return this.core.gameInputFields;
  }

  /** The scenario's game message kinds, sorted by name (payload fields in name order). */
  get gameMessageKinds(): readonly GameMessageKind[] {
    return this.core.gameMessageKinds;
  }

  /** The scenario's game state fields, sorted by name. */
  get gameStateFields(): readonly GameStateField[] {
    return this.core.gameState.fields;
  }

  /** The game state the scenario published, by field name (a frozen copy). */
  gameState(): GameStateValues {
    return this.live().gameState.named();
  }

  /** The game state values in field order (a copy), for the wire. */
  gameStateValues(): GameStateValue[] {
    return this.live().gameState.list();
  }

  /** Changes whenever the game state does (not part of the hash): equal versions mean equal state. */
  get gameStateVersion(): number {
    return this.core.gameState.version;
  }

  /** The physics world (read-only use: queries, body handles). Changing it directly breaks determinism. */
  get world(): PhysicsWorld {
    return this.live().world;
  }

  /** Applies one tick's input record and simulates 1/60 s. Throws (changing nothing) on a bad record. */
  step(record: TickInputRecord): SimEvent[] {
    const core = this.live();
    this.hashCache = null;
    this.readCache = null;
    return runTick(core, record).slice();
  }

  /** The 64-bit state hash after the last step, 16 lowercase hex characters. */
  stateHash(): string {
    const core = this.live();
    if (this.hashCache && this.hashCache.tick === core.tick) return this.hashCache.hash;
    const hash = hashState(core, this.readBodyStates());
    this.hashCache = { tick: core.tick, hash };
    return hash;
  }

  /** Everything the hash covers, copied out (for divergence reports). */
  dumpState(): StateDump {
    return dumpState(this.live());
  }

  /** The first difference between this simulation's state and another's (or a dump), or null when identical. */
  firstDivergence(other: Simulation | StateDump): Divergence | null {
    const theirs = other instanceof Simulation ? other.dumpState() : other;
    return firstDivergence(this.dumpState(), theirs);
  }

  /** Present players' characters, ascending player id. */
  characters(): CharacterState[] {
    return this.live().players.characterStates();
  }

  /** Bulk body state in id order, read once per tick (reused arrays, valid until the next step: copy what you keep). */
  readBodyStates(): BodyStates {
    const core = this.live();
    if (this.readCache !== null && this.readCache.tick === core.tick) return this.readCache.states;
    const states = core.world.readBodyStates();
    this.readCache = { tick: core.tick, states };
    return states;
  }

  /** How to draw a body, or undefined if there is none with that id. */
  bodyDescriptor(id: number): BodyDescriptor | undefined {
    return this.live().registry.get(id)?.descriptor;
  }

  /** Descriptors of every static body (the scene geometry), ascending id. */
  staticDescriptors(): BodyDescriptor[] {
    return this.live().registry.all().filter((r) => r.descriptor.motion === 'static').map((r) => r.descriptor);
  }

  /** Descriptors of every live body, ascending id. */
  descriptors(): BodyDescriptor[] {
    return this.live().registry.all().map((r) => r.descriptor);
  }

  /** Ids of present players, ascending. */
  playerIds(): number[] {
    return this.live().players.inOrder().map((p) => p.playerId);
  }

  /** A fast in-memory checkpoint (Jolt state on the WASM heap): dispose() it when done. */
  saveCheckpoint(): Checkpoint {
    return saveCheckpoint(this.live());
  }

  /** Returns to a checkpoint this simulation saved; later steps give the same hashes as after the save. */
  restoreCheckpoint(cp: Checkpoint): void {
    restoreCheckpoint(this.live(), cp);
    this.hashCache = null;
    this.readCache = null;
  }

  /** The checkpoint as self-describing, versioned bytes (for disk); restorable into any simulation of the same setup. */
  saveCheckpointBytes(): Uint8Array {
    const core = this.live();
    return encodeCheckpoint(core, captureData(core, 'saveCheckpointBytes'));
  }

  /** Restores saveCheckpointBytes() output (same scenario, params and seed; any process). */
  restoreCheckpointBytes(bytes: Uint8Array): void {
    decodeCheckpoint(this.live(), bytes);
    this.hashCache = null;
    this.readCache = null;
  }

  /** Frees the world and everything in it. */
  destroy(): void {
    if (this.destroyed) return;
    this.destroyed = true;
    for (const p of [...this.core.players.inOrder()]) this.core.players.remove(p.playerId);
    this.core.world.destroy();
  }

  /** Whether destroy() has run. */
  get isDestroyed(): boolean {
    return this.destroyed;
  }
}
