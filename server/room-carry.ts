// What a room takes along when it moves to another thread at a tick boundary: its simulation as checkpoint bytes,
// its players' input buffers, the join/leave/message queues of the next tick, the predict stream's coder state and
// where its input log goes on. Plain data only (it crosses a worker boundary by structured clone).
import type { PlayerInputState } from '../shared/protocol/record-delta.ts';
import type { GameMessage } from '../shared/sim/game-messages.ts';
import type { InputBufferState } from './input-buffer.ts';
import type { NetModeRequest } from './net-mode-policy.ts';
import type { ContinuedLog } from './recorder.ts';

/** One player of a moving room. */
export interface CarriedPlayer {
  playerId: number;
  name: string;
  /** Its join has gone into a record. */
  inWorld: boolean;
  /** Its link is down and the room holds its character. */
  held: boolean;
  inputs: InputBufferState;
}

/** A room stopped between two ticks, ready to go on elsewhere. */
export interface RoomCarry {
  id: string;
  scenario: string;
  params: Readonly<Record<string, number>>;
  seed: number | string;
  netModeRequested: NetModeRequest;
  /** The next tick to run (the checkpoint's tick). */
  tick: number;
  /** Simulation.saveCheckpointBytes() at `tick`. */
  checkpoint: Uint8Array;
  /** The state hash at `tick` (the new thread checks its restore against it). */
  hash: string;
  players: CarriedPlayer[];
  nextPlayerId: number;
  pendingLeaves: number[];
  /** Game messages waiting for their tick. */
  messages: Array<GameMessage & { tick: number }>;
  snapshotAccumulator: number;
  /** Ids of the scene's built static bodies still present (sent in welcomes, never in snapshots). */
  sceneStatics: number[];
  lastBodyCount: number;
  cpuSeconds: number;
  /** The predict feed's coder state after the last record (null: a snapshot-mode room). */
  predictInputs: PlayerInputState[] | null;
  /** Where the recording goes on (null: the room does not record). */
  log: ContinuedLog | null;
}
