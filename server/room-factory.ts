// Builds what a room runs on: a Simulation of a registered scenario on its own Jolt module instance (its own 128 MB
// heap, so rooms cannot starve or abort each other, and a room's heap history is its session's alone) and, with
// --record, the room's input-log recorder.
import { Simulation } from '../shared/sim/simulation.ts';
import type { ScenarioDefinition } from '../shared/sim/scenario.ts';
import type { Logger } from './logger.ts';
import { TICK_RATE_HZ } from '../shared/tick-rate.ts';
import { createRoomRecorder, DEFAULT_CHECKPOINT_EVERY_SECONDS, type ContinuedLog, type DurabilityOptions, type RoomRecording } from './recorder.ts';
import { scenarioModuleHash } from './scenario-module.ts';
import type { RoomFactory, RoomSimulationBuild } from './room-manager.ts';
import type { RoomRecorder, RoomSimulation } from './room.ts';

/** Where scenarios come from (scenarios/index.ts in the server; a fixed list in tests). */
export interface ScenarioSource {
  get(name: string): ScenarioDefinition | undefined;
  names(): readonly string[];
}

/** Options of createRoomFactory. */
export interface RoomFactoryOptions {
  scenarios: ScenarioSource;
  logger: Logger;
  /** Record every room's input log into this directory (null: no recording). */
  recordDir?: string | null;
  /** Hash records in logs every N ticks. Default 60. */
  hashEveryTicks?: number;
  /** When recorded records reach the disk. Default { mode: DEFAULT_DURABILITY }. */
  durability?: DurabilityOptions;
  /** A checkpoint in logs every N seconds of play (0: none). Default DEFAULT_CHECKPOINT_EVERY_SECONDS. */
  checkpointEverySeconds?: number;
  /**
   * Free WASM heap a new world needs before it is created (its own arrays + the 10 MB temp allocator + the
   * world's reserve). Measured: character-course ~15 MB, cubes-901 ~19 MB. Default 32 MiB.
   */
  minFreeHeapBytesForRoom?: number;
  /**
   * Give every room its own Jolt module instance (default true). With false, rooms share the process-wide module
   * and its 128 MB heap, guarded by minFreeHeapBytesForRoom.
   */
  isolateRooms?: boolean;
}

/** What the factory does for recordings beyond new rooms: resumed rooms' logs, and each open room's recording. */
export interface RecordingFactory {
  /** A recording that goes on appending to a resumed room's log. */
  continueRecording(room: { id: string; scenario: string; params: Readonly<Record<string, number>>; seed: number | string; sim: RoomSimulation }, log: ContinuedLog): Promise<RoomRecording>;
  /** The input log an open room of this factory records into (null: none). */
  recordingPath(roomId: string): string | null;
  /** RoomFactory.createSimulation, typed with the Simulation it builds (a resume restores checkpoints into it). */
  createSimulation(name: string, params: Readonly<Record<string, number>>, seed: number | string): Promise<RoomSimulationBuild & { sim: Simulation }>;
}

/**
 * A RoomFactory over Simulation.create with a heap guard and optional recording. It keeps no reference to an isolated
 * room's simulation: once the room closes and drops it, its Jolt module and 128 MB heap are garbage.
 */
export function createRoomFactory(opts: RoomFactoryOptions): RecordingFactory & RoomFactory & { liveSimulations(): number } {
  // The open rooms' recordings by room id (a recording leaves when it closes): resume keys go beside their logs.
  const recordings = new Map<string, RoomRecording>();
  const record = async (room: { id: string; scenario: string; params: Readonly<Record<string, number>>; seed: number | string; sim: RoomSimulation }, dir: string, continueLog?: ContinuedLog): Promise<RoomRecording> => {
    const sim = room.sim;
    const def = opts.scenarios.get(room.scenario);
    const recording: RoomRecording = await createRoomRecorder({
      durability: opts.durability,
      checkpointEveryTicks: Math.round((opts.checkpointEverySeconds ?? DEFAULT_CHECKPOINT_EVERY_SECONDS) * TICK_RATE_HZ),
      checkpoint: sim.saveCheckpointBytes ? () => sim.saveCheckpointBytes!() : undefined,
      dir,
      roomId: room.id,
      scenario: room.scenario,
      scenarioHash: def ? await scenarioModuleHash(def) : '',
      params: room.params,
      seed: room.seed,
      startTick: room.sim.tick,
      initialHash: room.sim.stateHash(),
      logger: opts.logger,
      hashEveryTicks: opts.hashEveryTicks,
      continueLog,
      onClose: () => {
        if (recordings.get(room.id) === recording) recordings.delete(room.id);
      },
    });
    recordings.set(room.id, recording);
    return recording;
  };
  // Shared-module mode only: the worlds on the process-wide heap, for the free-memory guard (destroyed ones pruned).
  const live = new Set<Simulation>();
  const need = opts.minFreeHeapBytesForRoom ?? 32 * 1024 * 1024;

  const prune = (): void => {
    for (const sim of live) if (sim.isDestroyed) live.delete(sim);
  };
  const freeHeap = (): number | null => {
    prune();
    for (const sim of live) return sim.world.freeHeapBytes();
    return null; // no world yet: the heap is fresh
  };

  return {
    /** Worlds open on the shared module (always 0 with isolated rooms, which this factory does not track). */
    liveSimulations: () => {
      prune();
      return live.size;
    },
    hasScenario: (name) => opts.scenarios.get(name) !== undefined,
    async createSimulation(name, params, seed): Promise<RoomSimulationBuild & { sim: Simulation }> {
      const def = opts.scenarios.get(name);
      if (!def) throw new Error(`unknown scenario "${name}" (known: ${opts.scenarios.names().join(', ')})`);
      const isolated = opts.isolateRooms ?? true;
      const free = isolated ? null : freeHeap();
      if (free !== null && free < need) {
        throw new Error(`not enough physics memory for another room: ${(free / 1048576).toFixed(1)} MiB free of the 128 MiB WASM heap, a room needs ${(need / 1048576).toFixed(0)} MiB; close a room first`);
      }
      const sim = await Simulation.create({ scenario: def, params, seed, worldOptions: { isolatedModule: isolated } });
      if (!isolated) live.add(sim);
      return { sim, maxBodies: sim.world.maxBodies, maxPlayers: sim.maxPlayers, params: { ...sim.params }, description: def.description, bounds: def.bounds, tickCostMs: def.tickCostMs };
    },
    async createRecorder(room): Promise<RoomRecorder | null> {
      if (!opts.recordDir) return null;
      return record(room, opts.recordDir);
    },
    continueRecording: (room, log) => record(room, '', log),
    recordingPath: (roomId) => recordings.get(roomId)?.path ?? null,
  };
}
