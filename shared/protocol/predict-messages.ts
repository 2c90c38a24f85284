// Messages of predict mode (docs/protocol.md): the server's checkpoint of the room and its confirmed tick input
// records (delta-coded, with a state hash every HASH_INTERVAL_TICKS), and the client's resync and net-mode requests.
import type { PlayerJoin } from '../sim/types.ts';
import type { PlayerInputState } from './record-delta.ts';

/** How a room serves its members: interpolated snapshots, or confirmed inputs for clients that run the simulation. */
export const NetMode = {
  Snapshot: 'snapshot',
  Predict: 'predict',
} as const;
export type NetMode = (typeof NetMode)[keyof typeof NetMode];

/** Whether a value names a net mode. */
export function isNetMode(value: unknown): value is NetMode {
  return value === NetMode.Snapshot || value === NetMode.Predict;
}

/** The server attaches the state hash to the record of every tick t with (t + 1) % HASH_INTERVAL_TICKS === 0. */
export const HASH_INTERVAL_TICKS = 30;

/** Whether the record of `tick` carries the state hash after it. */
export function carriesHash(tick: number): boolean {
  return (tick + 1) % HASH_INTERVAL_TICKS === 0;
}

/** Largest checkpoint the client accepts (bytes). */
export const MAX_CHECKPOINT_BYTES = 64 * 1024 * 1024;

/** The room's state: restore it into a simulation of the welcome's scenario and params with this seed. */
export interface CheckpointMessage {
  type: 'checkpoint';
  /** Ticks applied: the next record the client receives is for this tick. */
  tick: number;
  /** The room's PRNG seed (a simulation is created with it before the bytes restore). */
  seed: number | string;
  /** Simulation.saveCheckpointBytes() of the room at `tick`. */
  bytes: Uint8Array;
  /** The record coder's state at `tick`: every present player's last command (the baseline of the next record). */
  inputs: PlayerInputState[];
}

/** One confirmed tick input record (RecordDeltaCoder bits), with the state hash after it on hash ticks. */
export interface RecordMessage {
  type: 'record';
  /** The record's tick modulo 256 (the client knows the full tick: records arrive in order, one per tick). */
  tickLow: number;
  bits: Uint8Array;
  joins: PlayerJoin[];
  /** The 16-hex state hash after this tick, on ticks where carriesHash(tick); else null. */
  hash: string | null;
}

/** Asks for a fresh checkpoint (after a hash mismatch); the server answers at most about once a second. */
export interface ResyncMessage {
  type: 'resync';
}

/** Asks the server to serve this client in another net mode (a predicting client falling back to snapshots). */
export interface NetModeMessage {
  type: 'netMode';
  mode: NetMode;
}
