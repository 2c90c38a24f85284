// The scenario contract: a declarative, seeded scene module (name, parameters, static scene, per-tick hook, spawn
// points, render hints). Scenarios live in scenarios/; the Simulation builds and drives them through this interface.
import { describeValue } from './describe-value.ts';
import type { BodyHandle, BodyOptions, PhysicsWorldOptions, QuatLike, ShapeSpec, Vec3Like } from '../physics/index.ts';
import type { GameInputFieldSpec, GameInputValues } from './game-input.ts';
import type { GameMessageEvent, GameMessageSpec } from './game-messages.ts';
import type { GameStateFieldSpec } from './game-state.ts';
import type { Prng } from './prng.ts';
import type { CharacterState, PlayerCommand, SimEvent } from './types.ts';

/** One numeric parameter with its default and limits. */
export interface ParamSpec {
  default: number;
  min: number;
  max: number;
  integer?: boolean;
  description: string;
}

/** Resolved parameter values (every declared parameter present). */
export type ParamValues = Readonly<Record<string, number>>;

/** An RGB colour, components in [0, 1]. */
export type Rgb = readonly [number, number, number];

/** Body options plus what the client needs to draw the body. */
export interface SpawnOptions extends BodyOptions {
  /** Render colour; scenarios pick one per body kind. */
  color?: Rgb;
  /** Hide from the renderer (e.g. trigger volumes drawn only as outlines by the client). */
  hidden?: boolean;
}

/** How a scenario's players behave. */
export interface PlayerRules {
  /** Walk speed (m/s); sprint multiplies it by 1.8. Default 4. */
  walkSpeedMetresPerSecond?: number;
  /** Jump take-off speed (m/s). Default 5. */
  jumpSpeedMetresPerSecond?: number;
  /** Whether a player's bullets hit other players (never the shooter). Default false. */
  bulletsHitPlayers?: boolean;
  /** Ticks between two shots of one player. Default 10. */
  fireCooldownTicks?: number;
  /** Ticks a bullet lives. Default 120. */
  bulletLifetimeTicks?: number;
  /** Bullet muzzle speed (m/s). Default 40. */
  bulletSpeedMetresPerSecond?: number;
  /**
   * Most players in the game at once: the per-tick character budget. Rooms refuse joins past it with a reason, and a
   * tick record that would exceed it is rejected. Declare what the scene serves at 60 Hz on one core. Default 64.
   */
  maxPlayers?: number;
  /**
   * Highest step a character walks up by itself (m). Default 0.4. 0 turns stair walking off: a flat scene saves the
   * extra sweeps a character makes whenever something blocks its way (another player, a wall).
   */
  stepUpHeightMetres?: number;
  /** How far a character that walks off an edge snaps down to the floor (m); default 0.5, 0 turns it off. */
  stickToFloorMetres?: number;
}

/** What a scenario may use while building and on each tick. Every call is deterministic. */
export interface ScenarioContext {
  /** The world (advanced use: constraints, kinematic moves, queries). */
  readonly world: import('../physics/index.ts').PhysicsWorld;
  /** The simulation's seeded PRNG: the only randomness a scenario may use. */
  readonly rng: Prng;
  readonly params: ParamValues;
  /** The tick being simulated (0 while building). */
  readonly tick: number;
  /** Adds a body (static scene while building, a spawn during ticks: reported as bodySpawned). */
  spawn(shape: ShapeSpec, position: Vec3Like, rotation?: QuatLike | null, opts?: SpawnOptions): BodyHandle;
  /** Removes a body the scenario spawned (reported as bodyRemoved). */
  remove(bodyId: number): void;
  /** Reports a scenario event (e.g. 'doorOpen', 1). */
  emit(name: string, value: number): void;
  /** Characters currently in the world, by player id. */
  characters(): readonly CharacterState[];
  /** The commands applied this tick, sorted by player id (e.g. a player-driven body reads them). */
  inputs(): readonly PlayerCommand[];
  /** A present player's game-defined input values this tick, by field name (ScenarioDefinition.input). */
  gameInput(playerId: number): GameInputValues;
  /** Publishes a game state value (ScenarioDefinition.state): hashed, checkpointed and sent to clients when it changes. */
  setState(name: string, value: number | string): void;
  /** A game state value as last set (or its declared initial value). */
  getState(name: string): number | string;
}

/** The live side of a scenario, returned by build(). Keep body ids, not handles, across ticks. */
export interface ScenarioInstance {
  /** Feet position for the n-th player to join (n counts every join of the session). */
  spawnPoint(playerIndex: number): Vec3Like;
  /** Runs after the physics step of every tick (spawners, moving platforms, streaming). */
  onTick?(ctx: ScenarioContext): void;
  /** Runs for each game message of the tick, in record order, after joins and before commands (pick a team, …). */
  onMessage?(ctx: ScenarioContext, msg: GameMessageEvent): void;
  /** Sees the tick's sorted sensor events after onTick (doors, targets). */
  onEvents?(ctx: ScenarioContext, events: readonly SimEvent[]): void;
  /** Scenario-side state as plain JSON data, for checkpoints and the state hash. */
  saveState?(): number[];
  /** Restores what saveState returned. */
  restoreState?(state: readonly number[]): void;
}

/** A scenario module's default export shape (exported by name as `scenario`). */
export interface ScenarioDefinition {
  name: string;
  description: string;
  params: Readonly<Record<string, ParamSpec>>;
  /** Region every body stays in (snapshot quantization bounds); bodies leaving it are removed by the simulation. */
  bounds: { min: Vec3Like; max: Vec3Like };
  /** The scripted golden run: how many ticks, how many scripted bots. */
  golden: { ticks: number; bots: number };
  players?: PlayerRules;
  /**
   * Game-defined input fields players send beside the built-in command, by name: `{kind: 'button'}` (0 or 1) or
   * `{kind: 'axis', min, max}` (integers). At most 16; the SDK sends them by name (`setInput({...cmd, kick: 1})`).
   */
  input?: Readonly<Record<string, GameInputFieldSpec>>;
  /**
   * Replicated game state by name: `{kind: 'number', initial?}` or `{kind: 'string', maxLength? (≤ 64, default 32),
   * initial?}`. At most 32 fields. The scenario sets values with ctx.setState; clients get them with snapshots.
   */
  state?: Readonly<Record<string, GameStateFieldSpec>>;
  /**
   * Game messages players may send by name, each with a payload of named integer fields:
   * `{pickTeam: {payload: {team: {min: 0, max: 1}}}}`. At most 32 kinds of at most 8 fields. They reach
   * ScenarioInstance.onMessage on the tick the server stamps them with, and the input log records them.
   */
  messages?: Readonly<Record<string, GameMessageSpec>>;
  /**
   * Estimated time of one tick at default parameters with a few players (ms, one core of a quiet desktop; `npm run
   * bench` or `run` measures it). With it, `--net-mode auto` serves the scenario in predict mode when a client's
   * frame affords the rollback; without it, only when predict is asked for by name.
   */
  tickCostMs?: number;
  /** World limits (maxBodies, …) this scene needs. */
  world?: Omit<PhysicsWorldOptions, 'wasmBinary' | 'wasmUrl'>;
  /** Builds the static scene and returns the live instance. */
  build(ctx: ScenarioContext): ScenarioInstance;
}

/** Fills defaults and checks every parameter; unknown names and out-of-range values throw a clear Error. */
export function resolveParams(def: ScenarioDefinition, given: Readonly<Record<string, number>> = {}): ParamValues {
  const out: Record<string, number> = {};
  for (const key of Object.keys(given)) {
    if (!Object.prototype.hasOwnProperty.call(def.params, key)) {
      const known = Object.keys(def.params).join(', ') || '(none)';
      throw new Error(`scenario ${def.name}: unknown parameter "${key}" (known: ${known})`);
    }
  }
  for (const [key, spec] of Object.entries(def.params)) {
    const value = Object.prototype.hasOwnProperty.call(given, key) ? given[key] : spec.default;
    if (typeof value !== 'number' || !Number.isFinite(value)) throw new Error(`scenario ${def.name}: parameter ${key} must be a finite number, got ${describeValue(value)}`);
    if (spec.integer && !Number.isInteger(value)) throw new Error(`scenario ${def.name}: parameter ${key} must be an integer, got ${value}`);
    if (value < spec.min || value > spec.max) throw new Error(`scenario ${def.name}: parameter ${key} must be in [${spec.min}, ${spec.max}], got ${value}`);
    out[key] = value;
  }
  return Object.freeze(out);
}
