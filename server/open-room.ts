// Opens one room on the calling thread: its simulation from the factory, its recorder, and the Room around them.
// The room manager uses it for rooms on the main thread, a room worker for its own rooms.
import type { Clock } from '../shared/clock.ts';
import { ErrorCode } from '../shared/protocol/opcodes.ts';
import type { CatchUpGate } from './catch-up-budget.ts';
import type { TickPhases } from './tick-phases.ts';
import type { Logger } from './logger.ts';
import type { ServerMetrics } from './metrics.ts';
import { decideNetMode } from './net-mode-policy.ts';
import { Room, RoomError, type RoomRecorder } from './room.ts';
import type { PlayerInputState } from '../shared/protocol/record-delta.ts';
import type { RoomFactory, RoomSimulationBuild, RoomSpec } from './room-manager.ts';
import type { RoomCarry } from './room-carry.ts';

/** What openRoom needs besides the spec. */
export interface OpenRoomOptions {
  factory: RoomFactory;
  clock: Clock;
  metrics: ServerMetrics;
  logger: Logger;
  snapshotRateHz: number;
  maxClientsPerRoom: number;
  maxCatchUpTicks?: number;
  maxInputLeadTicks?: number;
  pauseWhenEmpty?: boolean;
  /** The catch-up budget of the calling thread (its rooms share it). */
  catchUp?: CatchUpGate | null;
  /** The tick phases of the calling thread (each room takes one, spread over the tick period). */
  phases?: TickPhases | null;
}

/** Builds a room (not started); throws RoomError for a bad scenario or parameters, or a recording that cannot start. */
export async function openRoom(spec: RoomSpec, opts: OpenRoomOptions): Promise<Room> {
  const { id, scenario, params, seed } = spec;
  let built: RoomSimulationBuild;
  try {
    built = await opts.factory.createSimulation(scenario, params, seed);
  } catch (error) {
    throw new RoomError(ErrorCode.BadMessage, `cannot create room ${id}: ${error instanceof Error ? error.message : String(error)}`);
  }
  let recorder: RoomRecorder | null = null;
  try {
    recorder = (await opts.factory.createRecorder?.({ id, scenario, params: built.params, seed, sim: built.sim })) ?? null;
  } catch (error) {
    built.sim.destroy();
    throw new RoomError(ErrorCode.Internal, `cannot start the recording of room ${id}: ${error instanceof Error ? error.message : String(error)}`);
  }
  return roomAround(spec, built, recorder, opts);
}

/**
 * The Room (not started) around a built simulation and its recorder (a resumed room's comes from its log; a room
 * moving in from another thread brings its state in `carried`).
 */
export function roomAround(spec: RoomSpec, built: RoomSimulationBuild, recorder: RoomRecorder | null, opts: Omit<OpenRoomOptions, 'factory'>, predictInputs?: readonly PlayerInputState[], carried?: RoomCarry): Room {
  const { id, scenario, seed } = spec;
  const netModeRequested = spec.netMode ?? 'auto';
  const decision = decideNetMode(netModeRequested, scenario, built.params, built.tickCostMs);
  return new Room(built.sim, {
    id,
    netMode: decision.mode,
    netModeRequested,
    netModeNote: decision.note,
    scenarioName: scenario,
    description: built.description,
    bounds: built.bounds,
    params: built.params,
    seed,
    clock: opts.clock,
    metrics: opts.metrics,
    logger: opts.logger,
    snapshotRateHz: opts.snapshotRateHz,
    maxClients: opts.maxClientsPerRoom,
    maxBodies: built.maxBodies,
    maxPlayers: built.maxPlayers,
    maxCatchUpTicks: opts.maxCatchUpTicks,
    maxInputLeadTicks: opts.maxInputLeadTicks,
    pauseWhenEmpty: opts.pauseWhenEmpty,
    recorder,
    catchUp: opts.catchUp,
    phases: opts.phases,
    predictInputs,
    carried,
  });
}
