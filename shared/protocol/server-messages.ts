// Messages the server sends to a client, as typed objects (the wire form of each is in codec.ts and
// docs/protocol.md). The client decodes them with server-message-decoder.ts.
import type { GameStateValue } from '../sim/game-state.ts';
import type { BodyDescriptor, SimEvent } from '../sim/types.ts';
import type { ByeReason, ErrorCode } from './opcodes.ts';
import type { GameSchemaInfo } from './game-schema-codec.ts';
import type { CheckpointMessage, NetMode, RecordMessage } from './predict-messages.ts';
import type { Bounds, SnapshotFormatSpec } from './quantization.ts';

/** What a client needs to know about the room's scenario. */
export interface ScenarioInfo {
  name: string;
  description: string;
  /** Resolved parameter values. */
  params: Record<string, number>;
  /** The region bodies live in (also the snapshot position grid). */
  bounds: Bounds;
  /** The scenario's game-defined input (and, later, state and messages); absent parts: none declared. */
  game?: GameSchemaInfo;
}

/** Answer to hello: who you are, where the room's clock stands, and everything needed to draw the world. */
export interface WelcomeMessage {
  type: 'welcome';
  protocolVersion: number;
  playerId: number;
  roomId: string;
  /** The room's simulation tick when the welcome was sent (ticks applied so far). */
  tick: number;
  tickRateHz: number;
  snapshotRateHz: number;
  scenario: ScenarioInfo;
  /** Snapshot quantization; with scenario.bounds it gives the client the server's exact SnapshotFormat. */
  snapshotFormat: SnapshotFormatSpec;
  /** Static geometry (sent once; snapshots never carry static bodies). */
  staticBodies: BodyDescriptor[];
  /** Descriptors of the non-static bodies alive now (snapshots only add descriptors for later spawns). */
  dynamicBodies: BodyDescriptor[];
  /** Secret that lets a new connection take this player back after a drop (single use; null: resume is off). */
  resumeToken: string | null;
  /** How long (ms) the server holds this player after its connection drops without a bye (0: not at all). */
  resumeGraceMs: number;
  /** True when this welcome handed back a held player (same player id and character) instead of a new one. */
  resumed: boolean;
  /** How the room serves its members; in predict mode a checkpoint follows the welcome and records every tick. */
  netMode: NetMode;
  /**
   * Predict mode: ticks between an own command and the local tick that applies it (0: the next tick; at most
   * MAX_INPUT_DELAY_TICKS). The room's default; a client may choose its own. 0 in snapshot rooms.
   */
  inputDelayTicks: number;
}

/** Answer to ping. */
export interface PongMessage {
  type: 'pong';
  /** Echo of ping.clientTimeMs. */
  clientTimeMs: number;
  /** Ticks the room had applied when the pong was sent. */
  serverTick: number;
  /** The server's monotonic clock (ms) when the pong was sent. */
  serverTimeMs: number;
  /** Ticks so far at which this player's input had not arrived and the server repeated the previous one. */
  missedInputTicks: number;
  /** Ticks the player's room ran over the last second, rounded (60 when it keeps up). */
  roomTicksPerSecond: number;
  /** True while the room cannot keep the tick rate and runs slowed (only that room). */
  roomSlow: boolean;
}

/** One snapshot: the encoded frame plus descriptors of newly spawned bodies the client may not have. */
export interface SnapshotMessage {
  type: 'snapshot';
  bytes: Uint8Array;
  descriptors: BodyDescriptor[];
  /** The whole game state (values in the welcome's state-field order), present only when it changed since the last one sent. */
  state?: GameStateValue[];
}

/** Simulation events (sensor, join/leave, spawn/remove, scenario), reliable and in tick order. */
export interface EventsMessage {
  type: 'events';
  events: SimEvent[];
}

/** Something the client sent was refused; the connection stays open unless a bye follows. */
export interface ErrorMessage {
  type: 'error';
  code: ErrorCode;
  message: string;
}

/** The server is ending the session; the socket closes right after. */
export interface ServerByeMessage {
  type: 'bye';
  reason: ByeReason;
  message: string;
  /** With reason `room-moved`: the WebSocket URL (ws:// or wss://) of the server that hosts the room. */
  url?: string;
}

/** Every server→client message. */
export type ServerMessage = WelcomeMessage | PongMessage | SnapshotMessage | EventsMessage | ErrorMessage | ServerByeMessage | CheckpointMessage | RecordMessage;
