// A room's public shapes: its settings, what a join gives, its summary, its refusals, and what a held player applies.
// room.ts implements the room and re-exports these.
import type { Vec3Like } from '../shared/physics/index.ts';
import { ErrorCode } from '../shared/protocol/opcodes.ts';
import type { NetMode } from '../shared/protocol/predict-messages.ts';
import type { PlayerInputState } from '../shared/protocol/record-delta.ts';
import type { InputCommand } from '../shared/sim/input.ts';
import type { CatchUpGate } from './catch-up-budget.ts';
import type { TickPhases } from './tick-phases.ts';
import type { Logger } from './logger.ts';
import type { ServerMetrics } from './metrics.ts';
import type { NetModeRequest } from './net-mode-policy.ts';
import type { RoomRecorder } from './room-contracts.ts';
import type { RoomCarry } from './room-carry.ts';
import type { PaceReport } from './room-pace.ts';
import type { Clock } from '../shared/clock.ts';

/** A refusal with a stable code the session forwards to the client. */
export class RoomError extends Error {
  readonly code: ErrorCode;
  constructor(code: ErrorCode, message: string) {
    super(message);
    this.name = 'RoomError';
    this.code = code;
  }
}

/** Room settings. */
export interface RoomOptions {
  id: string;
  scenarioName: string;
  /** The scenario's description (for the welcome message). */
  description?: string;
  /** The scenario's bounds: where bodies live (the snapshot position grid). */
  bounds?: { min: Vec3Like; max: Vec3Like };
  params: Readonly<Record<string, number>>;
  seed: number | string;
  clock: Clock;
  metrics: ServerMetrics;
  logger: Logger;
  /** Snapshots per second (≤ tick rate); a frame goes out on ticks where the running count crosses a whole number. */
  snapshotRateHz: number;
  /** Most members; joins beyond it are refused. */
  maxClients: number;
  /** Most bodies the world may hold; a join that would need more is refused. */
  maxBodies: number;
  /** Most players the scenario serves (its per-tick character budget); joins beyond it are refused. Default none. */
  maxPlayers?: number;
  /** Most ticks ahead of the server an input may be stamped. Default 120 (2 s). */
  maxInputLeadTicks?: number;
  /** Most ticks run back to back to catch up before slowing down. Default 4. */
  maxCatchUpTicks?: number;
  /** Stop ticking while nobody is in the room. Default true. */
  pauseWhenEmpty?: boolean;
  recorder?: RoomRecorder | null;
  /** The catch-up budget of the thread the room runs on (shared by its rooms). Default none. */
  catchUp?: CatchUpGate | null;
  /** The tick phases of the thread the room runs on: it takes one at creation and gives it back when it closes. */
  phases?: TickPhases | null;
  /** A resumed room's players already in the game with their last commands, for predict mode's record stream. */
  predictInputs?: readonly PlayerInputState[];
  /** A room moving in from another thread goes on from this state; its connected players' members reattach() before start(). */
  carried?: RoomCarry;
  /** How the room serves its members (decided by net-mode-policy.ts). Default snapshot. */
  netMode?: NetMode;
  /** The mode the room was asked for. Default: netMode. */
  netModeRequested?: NetModeRequest;
  /** Why the room serves snapshots although predict was asked for or allowed. */
  netModeNote?: string | null;
}

/** What a successful join gives the member. */
export interface JoinResult {
  playerId: number;
  /** The tick whose record carries the join. */
  joinTick: number;
  /** The first tick the player's inputs are applied on. */
  firstInputTick: number;
}

/** A room's public summary (GET /api/rooms): who is in it, and its pace (ticksPerSecond, slow). */
export interface RoomInfo extends PaceReport {
  id: string;
  scenario: string;
  clients: number;
  tick: number;
  bodies: number;
  params: Readonly<Record<string, number>>;
  /** 'snapshot' or 'predict'. */
  netMode: NetMode;
  /** Why the room serves snapshots although predict was asked for or allowed (absent otherwise). */
  netModeNote?: string;
  /** The room worker it runs in, and how often it moved to another one (absent: rooms on the main thread). */
  worker?: number;
  moves?: number;
}

/** What a held player (link down, character kept) applies each tick: no movement, no buttons, same look direction. */
export function heldInput(last: InputCommand): InputCommand {
  return { moveX: 0, moveZ: 0, yaw: last.yaw, pitch: last.pitch, buttons: 0 };
}
