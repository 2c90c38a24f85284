// The simulation's data contracts: per-tick input records (exactly what the log stores), events, players, and the
// character state other layers (hash, snapshots, render) read. Plain data only: no Jolt, no classes.
import type { ShapeSpec } from '../physics-data/shape-spec.ts';
import type { Vec3Like } from '../physics-data/vectors.ts';
import type { GameMessage } from './game-messages.ts';
import type { InputCommand } from './input.ts';

/** A player entering on this tick. Player ids are chosen by the host (server or recorder), unique per session. */
export interface PlayerJoin {
  playerId: number;
  name: string;
}

/** One player's command for this tick. */
export interface PlayerCommand {
  playerId: number;
  input: InputCommand;
}

/**
 * Everything that enters the simulation on one tick, in application order: leaves, then joins, then game messages,
 * then commands. This is exactly what the input log stores per tick. Arrays are sorted by playerId (messages keep
 * their arrival order within one player).
 */
export interface TickInputRecord {
  tick: number;
  leaves: number[];
  joins: PlayerJoin[];
  commands: PlayerCommand[];
  /** Game messages stamped for this tick (ScenarioDefinition.messages); absent or empty when there are none. */
  messages?: GameMessage[];
}

/** An empty record for a tick. */
export function emptyTickInput(tick: number): TickInputRecord {
  return { tick, leaves: [], joins: [], commands: [] };
}

/** Events the simulation reports, stamped with the tick that produced them; delivered in a deterministic order. */
export type SimEvent =
  | { type: 'sensorEnter'; tick: number; sensorId: number; bodyId: number; playerId?: number }
  | { type: 'sensorExit'; tick: number; sensorId: number; bodyId: number; playerId?: number }
  | { type: 'playerJoined'; tick: number; playerId: number; name: string; bodyId?: number }
  | { type: 'playerLeft'; tick: number; playerId: number }
  | { type: 'bodySpawned'; tick: number; bodyId: number }
  | { type: 'bodyRemoved'; tick: number; bodyId: number }
  | { type: 'scenario'; tick: number; name: string; value: number };

export type SimEventType = SimEvent['type'];

/** A player's character as other layers see it (copies; the simulation owns the controller). */
export interface CharacterState {
  playerId: number;
  /** Stable id of the character's inner body (hittable capsule). */
  bodyId: number;
  /** Feet position (m). */
  position: Vec3Like;
  velocity: Vec3Like;
  yaw: number;
  pitch: number;
  groundState: 'ground' | 'steep' | 'air' | 'unsupported';
  buttons: number;
}

/** What a client needs to draw a body: its shape, colour and motion kind (static geometry and spawns). */
export interface BodyDescriptor {
  id: number;
  shape: ShapeSpec;
  color: readonly [number, number, number];
  motion: 'static' | 'dynamic' | 'kinematic';
  hidden: boolean;
  /** Character capsules carry their player id. */
  playerId?: number;
  /** Initial pose (static bodies never move, so this is where to draw them). */
  position: Vec3Like;
  rotation: { x: number; y: number; z: number; w: number };
}
