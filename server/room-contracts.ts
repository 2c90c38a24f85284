// What a room and its collaborators agree on: the simulation it drives, the recorder it writes to, the world frame
// it shares with encoders and the member it delivers to. Plain contracts; room.ts implements the room itself.
import type { GameInputField } from '../shared/sim/game-input.ts';
import type { GameMessageKind } from '../shared/sim/game-messages.ts';
import type { GameStateField, GameStateValue } from '../shared/sim/game-state.ts';
import type { BodyDescriptor, CharacterState, SimEvent, TickInputRecord } from '../shared/sim/types.ts';
import type { ContinuedLog } from './recorder.ts';

/** The bulk body read the room hands to snapshot encoders (the world's readBodyStates() shape). */
export interface BodyStates {
  count: number;
  ids: Uint32Array;
  states: Float32Array;
  flags: Uint8Array;
}

/** The part of Simulation a room drives (shared/sim/simulation.ts satisfies it). */
export interface RoomSimulation {
  readonly tick: number;
  step(record: TickInputRecord): SimEvent[];
  stateHash(): string;
  characters(): CharacterState[];
  readBodyStates(): BodyStates;
  staticDescriptors(): BodyDescriptor[];
  bodyDescriptor(id: number): BodyDescriptor | undefined | null;
  destroy(): void;
  /** The scenario's game input fields (name order); absent or empty: none. */
  readonly gameInputFields?: readonly GameInputField[];
  /** The scenario's game message kinds (name order); absent or empty: none. */
  readonly gameMessageKinds?: readonly GameMessageKind[];
  /** The scenario's game state fields (name order); absent or empty: none. */
  readonly gameStateFields?: readonly GameStateField[];
  /** Changes whenever the game state does. */
  readonly gameStateVersion?: number;
  /** The game state values in field order. */
  gameStateValues?(): GameStateValue[];
  /** The simulation's byte checkpoint (for checkpoints in recordings), when it has one. */
  saveCheckpointBytes?(): Uint8Array;
  /** The world's WASM heap (for /metrics), when the simulation has one. */
  readonly world?: { freeHeapBytes(): number; totalHeapBytes(): number };
}

/** Where a room's input records go (the --record writer). A recorder never throws into the room. */
export interface RoomRecorder {
  /** The exact record about to be stepped (write-ahead). */
  append(record: TickInputRecord): void;
  /** After the step; `tick` is the simulation's tick counter now, `hash` computes its state hash on demand. */
  afterStep(tick: number, hash: () => string): void;
  /** Writes the end record (none when the hash is null: the room failed), flushes and closes. */
  close(finalTick: number, finalHash: string | null): Promise<void>;
  /**
   * Calls `send` (the tick's events and frame) once the log holds the tick durably, in tick order; absent: at once.
   * This is how nothing a client sees can be missing from the log after a crash (--durability tick).
   */
  release?(tick: number, send: () => void): void;
  /**
   * Lets go of the log without an end record once every record is durable and every held send released, so a room
   * moving to another thread goes on appending to the same file; null when the recording had stopped already.
   */
  handOff?(): Promise<ContinuedLog | null>;
}

/** The world after one snapshot tick, shared by every member's encoder (copies: valid after the tick). */
export interface WorldFrame {
  /** The tick just simulated (events of that tick carry the same number). */
  tick: number;
  bodies: BodyStates;
  characters: readonly CharacterState[];
  /**
   * Descriptors of the frame's dynamic bodies as of its tick, when the frame leaves later than its tick (a durable
   * recording holds it back until the tick is on disk) and a body spawned in it may be gone by then.
   */
  descriptors?: ReadonlyMap<number, BodyDescriptor>;
}

/** What a room needs from each connected member (the client session implements it). */
export interface RoomMember {
  /** The tick's events (sorted, stamped), delivered reliably; called only for ticks that have events. */
  deliverEvents(tick: number, events: readonly SimEvent[]): void;
  /** A world frame at the member's snapshot rate. */
  deliverFrame(frame: WorldFrame): void;
  /** The room has closed; the member is no longer in it. */
  roomClosed(reason: string): void;
  /** The room removed this member (its delivery failed); the room goes on. */
  removed(reason: string): void;
  /** Predict mode: the framed confirmed record of `tick` (every tick, in order). */
  deliverRecord?(tick: number, message: Uint8Array): void;
  /** Whether the member takes records now (streams them or waits for its checkpoint); absent: whenever it has deliverRecord. */
  takesRecords?(): boolean;
}
