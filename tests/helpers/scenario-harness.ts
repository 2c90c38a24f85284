// Test harness for scenarios: a ScenarioContext over a PhysicsWorld + Prng that steps a scenario the way the
// Simulation does (inputs → characters move → physics step → onTick → sorted sensor events → onEvents), with
// simple walking characters, spawn/remove/emit bookkeeping and bounds removal. Tests only; not the Simulation.
import '../../server/physics-node.ts';
import { CharacterController, CollisionLayer, PhysicsWorld, type BodyHandle, type QuatLike, type ShapeSpec, type Vec3Like } from '../../shared/physics/index.ts';
import { walkVelocity } from '../../shared/sim/controls.ts';
import { Button, NEUTRAL_INPUT, type InputCommand } from '../../shared/sim/input.ts';
import { gameInputValues, resolveGameInputFields } from '../../shared/sim/game-input.ts';
import { GameStateStore, resolveGameStateFields } from '../../shared/sim/game-state.ts';
import { Prng } from '../../shared/sim/prng.ts';
import { resolveParams, type ParamValues, type ScenarioContext, type ScenarioDefinition, type ScenarioInstance, type SpawnOptions } from '../../shared/sim/scenario.ts';
import type { CharacterState, PlayerCommand, SimEvent } from '../../shared/sim/types.ts';
import { TICK_DT_SECONDS } from '../../shared/tick-rate.ts';

/** Options of ScenarioHarness.create. */
export interface HarnessOptions {
  params?: Record<string, number>;
  seed?: number | string;
}

interface Player {
  playerId: number;
  controller: CharacterController;
  input: InputCommand;
}

/** Drives one scenario instance over its own world; call destroy() when done. */
export class ScenarioHarness {
  readonly def: ScenarioDefinition;
  readonly world: PhysicsWorld;
  readonly rng: Prng;
  readonly params: ParamValues;
  instance!: ScenarioInstance;
  /** Ticks stepped so far. */
  tick = 0;
  /** Every event so far, in delivery order. */
  readonly events: SimEvent[] = [];
  /** Spawn options (colour, hidden) by body id, for bodies the scenario spawned and still holds. */
  readonly spawnOptions = new Map<number, SpawnOptions>();
  private readonly players = new Map<number, Player>();
  private joinCount = 0;
  private currentTick = 0;
  private tickEvents: SimEvent[] = [];
  private tickInputs: PlayerCommand[] = [];
  private building = true;
  readonly ctx: ScenarioContext;
  /** The game state the scenario publishes. */
  readonly gameState: GameStateStore;

  private constructor(def: ScenarioDefinition, world: PhysicsWorld, rng: Prng, params: ParamValues) {
    this.def = def;
    this.world = world;
    this.rng = rng;
    this.params = params;
    this.gameState = new GameStateStore(resolveGameStateFields(def.state, def.name));
    const self = this;
    this.ctx = {
      world,
      rng,
      params,
      get tick() {
        return self.currentTick;
      },
      spawn: (shape, position, rotation, opts) => this.spawn(shape, position, rotation ?? null, opts ?? {}),
      remove: (bodyId) => this.remove(bodyId),
      emit: (name, value) => {
        if (typeof name !== 'string' || name.length === 0 || !Number.isFinite(value)) throw new Error(`emit: bad scenario event (${String(name)}, ${value})`);
        this.tickEvents.push({ type: 'scenario', tick: this.currentTick, name, value });
      },
      characters: () => this.characters(),
      inputs: () => this.tickInputs,
      setState: (name, value) => this.gameState.set(name, value),
      getState: (name) => this.gameState.get(name),
      gameInput: (playerId) => {
        const cmd = this.tickInputs.find((c) => c.playerId === playerId);
        if (!cmd) throw new Error(`gameInput: player ${playerId} has no command this tick`);
        return gameInputValues(cmd.input.game, resolveGameInputFields(def.input, def.name));
      },
    };
  }

  /** Resolves params, builds the world and the scene. */
  static async create(def: ScenarioDefinition, opts: HarnessOptions = {}): Promise<ScenarioHarness> {
    const params = resolveParams(def, opts.params ?? {});
    const world = await PhysicsWorld.create(def.world ?? {});
    const h = new ScenarioHarness(def, world, new Prng(opts.seed ?? 1), params);
    try {
      h.instance = def.build(h.ctx);
    } catch (err) {
      world.destroy();
      throw err;
    }
    h.tickEvents = [];
    h.building = false;
    return h;
  }

  private spawn(shape: ShapeSpec, position: Vec3Like, rotation: QuatLike | null, opts: SpawnOptions): BodyHandle {
    const handle = this.world.addShape(shape, position, rotation, opts);
    this.spawnOptions.set(handle.id, opts);
    if (!this.building) this.tickEvents.push({ type: 'bodySpawned', tick: this.currentTick, bodyId: handle.id });
    return handle;
  }

  private remove(bodyId: number): void {
    if (!this.spawnOptions.has(bodyId)) throw new Error(`remove: body ${bodyId} was not spawned by the scenario (or is gone)`);
    this.world.removeBody(bodyId);
    this.spawnOptions.delete(bodyId);
    this.tickEvents.push({ type: 'bodyRemoved', tick: this.currentTick, bodyId });
  }

  /** Adds a walking character for `playerId` at the scenario's next spawn point. */
  join(playerId: number): CharacterController {
    if (this.players.has(playerId)) throw new Error(`join: player ${playerId} is already in`);
    const position = this.instance.spawnPoint(this.joinCount++);
    const controller = new CharacterController(this.world, { position, layer: CollisionLayer.Player, name: `player ${playerId}` });
    this.players.set(playerId, { playerId, controller, input: { ...NEUTRAL_INPUT } });
    return controller;
  }

  /** Removes a player's character. */
  leave(playerId: number): void {
    const p = this.players.get(playerId);
    if (!p) throw new Error(`leave: no player ${playerId}`);
    p.controller.destroy();
    this.players.delete(playerId);
  }

  /** Sets the command a player holds from the next tick on. */
  setInput(playerId: number, input: Partial<InputCommand>): void {
    const p = this.players.get(playerId);
    if (!p) throw new Error(`setInput: no player ${playerId}`);
    p.input = { ...NEUTRAL_INPUT, ...input };
  }

  /** The character of a player. */
  controller(playerId: number): CharacterController {
    const p = this.players.get(playerId);
    if (!p) throw new Error(`controller: no player ${playerId}`);
    return p.controller;
  }

  private characters(): CharacterState[] {
    return [...this.players.values()]
      .sort((a, b) => a.playerId - b.playerId)
      .map((p) => ({
        playerId: p.playerId,
        bodyId: p.controller.body!.id,
        position: p.controller.position,
        velocity: { ...p.controller.velocity },
        yaw: p.input.yaw,
        pitch: p.input.pitch,
        groundState: p.controller.groundState,
        buttons: p.input.buttons,
      }));
  }

  /** One 60 Hz tick; returns its events. */
  step(): SimEvent[] {
    this.currentTick = this.tick;
    const ordered = [...this.players.values()].sort((a, b) => a.playerId - b.playerId);
    this.tickInputs = ordered.map((p) => ({ playerId: p.playerId, input: p.input }));
    const walk = this.def.players?.walkSpeedMetresPerSecond ?? 4;
    for (const p of ordered) {
      const v = walkVelocity(p.input, walk, (p.input.buttons & Button.Sprint) !== 0);
      p.controller.velocity.x = v.x;
      p.controller.velocity.z = v.z;
      if (p.input.buttons & Button.Jump) p.controller.jump(this.def.players?.jumpSpeedMetresPerSecond ?? 5);
      p.controller.move(TICK_DT_SECONDS);
    }
    const sensorEvents = this.world.stepFixed();
    this.instance.onTick?.(this.ctx);
    const playerOfBody = new Map(ordered.map((p) => [p.controller.body!.id, p.playerId]));
    const sensor: SimEvent[] = sensorEvents.map((e) => {
      const playerId = playerOfBody.get(e.otherId);
      const base = { tick: this.currentTick, sensorId: e.sensorId, bodyId: e.otherId };
      const withPlayer = playerId === undefined ? base : { ...base, playerId };
      return e.kind === 'enter' ? { type: 'sensorEnter' as const, ...withPlayer } : { type: 'sensorExit' as const, ...withPlayer };
    });
    this.instance.onEvents?.(this.ctx, sensor);
    this.removeOutOfBounds();
    const events = [...sensor, ...this.tickEvents];
    this.tickEvents = [];
    this.events.push(...events);
    this.tick++;
    return events;
  }

  /** Steps `ticks` ticks; returns all their events. */
  run(ticks: number): SimEvent[] {
    const out: SimEvent[] = [];
    for (let i = 0; i < ticks; i++) out.push(...this.step());
    return out;
  }

  private removeOutOfBounds(): void {
    const { min, max } = this.def.bounds;
    for (const id of [...this.spawnOptions.keys()].sort((a, b) => a - b)) {
      const h = this.world.getBody(id);
      if (!h || h.motion === 'static') continue;
      const p = h.position();
      if (p.x < min.x || p.y < min.y || p.z < min.z || p.x > max.x || p.y > max.y || p.z > max.z) this.remove(id);
    }
  }

  /** Ids of live bodies the scenario spawned, ascending. */
  scenarioBodyIds(): number[] {
    return [...this.spawnOptions.keys()].filter((id) => this.world.getBody(id)).sort((a, b) => a - b);
  }

  /** Handles of the scenario's dynamic bodies, by id. */
  dynamicBodies(): BodyHandle[] {
    return this.scenarioBodyIds()
      .map((id) => this.world.getBody(id)!)
      .filter((h) => h.motion === 'dynamic');
  }

  /** A copy of every body's state (13 floats per body, id order) plus the ids. */
  snapshot(): { ids: number[]; states: number[] } {
    const s = this.world.readBodyStates();
    return { ids: [...s.ids], states: [...s.states] };
  }

  /** Scenario events named `name` so far. */
  scenarioEvents(name: string): Array<Extract<SimEvent, { type: 'scenario' }>> {
    return this.events.filter((e): e is Extract<SimEvent, { type: 'scenario' }> => e.type === 'scenario' && e.name === name);
  }

  /** Frees the world and every character. */
  destroy(): void {
    for (const p of this.players.values()) p.controller.destroy();
    this.players.clear();
    this.world.destroy();
  }
}
