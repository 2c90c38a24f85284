// The process's rooms: the default room, rooms created on demand from a scenario, lookup by id, the rooms limit,
// and closing a room once it has been empty for a grace period (never the default room). Rooms run on this thread, or
// wherever a RoomHost opens them (the room workers).
import type { Clock, TimerHandle } from '../shared/clock.ts';
import { ErrorCode } from '../shared/protocol/opcodes.ts';
import type { CatchUpGate } from './catch-up-budget.ts';
import type { TickPhases } from './tick-phases.ts';
import type { HostedRoom } from './hosted-room.ts';
import type { Logger } from './logger.ts';
import type { ServerMetrics } from './metrics.ts';
import { NetMode } from '../shared/protocol/predict-messages.ts';
import type { PlayerInputState } from '../shared/protocol/record-delta.ts';
import type { NetModeRequest } from './net-mode-policy.ts';
import { openRoom, roomAround } from './open-room.ts';
import { Room, RoomError, type RoomInfo, type RoomRecorder, type RoomSimulation } from './room.ts';

/** The id of the room that always exists. */
export const DEFAULT_ROOM_ID = 'default';
/** Room ids: letters, digits, '-' and '_' (1–64). */
const ROOM_ID_RE = /^[A-Za-z0-9_-]{1,64}$/;

/** Whether `id` is a well-formed room id. */
export function isRoomId(id: string): boolean {
  return ROOM_ID_RE.test(id);
}

/** A simulation built for a room, with the limit the room enforces on joins. */
export interface RoomSimulationBuild {
  sim: RoomSimulation;
  description: string;
  bounds: { min: { x: number; y: number; z: number }; max: { x: number; y: number; z: number } };
  /** Most bodies the world holds. */
  maxBodies: number;
  /** Most players the scenario serves (its per-tick character budget); absent: no cap beyond the room's. */
  maxPlayers?: number;
  /** The parameters after defaults were filled in. */
  params: Readonly<Record<string, number>>;
  /** The scenario's own tick cost estimate at default parameters (ScenarioDefinition.tickCostMs), if it gives one. */
  tickCostMs?: number;
}

/** Builds simulations and recorders for rooms (the server wires Simulation.create and the log writer in here). */
export interface RoomFactory {
  /** Throws an Error with a clear message for an unknown scenario or bad parameters. */
  createSimulation(scenario: string, params: Readonly<Record<string, number>>, seed: number | string): Promise<RoomSimulationBuild>;
  /** A recorder for the room, or null when not recording. */
  createRecorder?(room: { id: string; scenario: string; params: Readonly<Record<string, number>>; seed: number | string; sim: RoomSimulation }): Promise<RoomRecorder | null>;
  /** Whether `scenario` names a known scenario. */
  hasScenario(scenario: string): boolean;
  /** The input log an open room records into (null: none), for resume keys. */
  recordingPath?(roomId: string): string | null;
}

/** A room to open: what a RoomHost is asked for. */
export interface RoomSpec {
  id: string;
  scenario: string;
  params: Readonly<Record<string, number>>;
  seed: number | string;
  /** The net mode asked for (openRoom decides the room's mode from it and the scenario's cost). Default 'auto'. */
  netMode?: NetModeRequest;
}

/** Fleet-wide room ids (server/fleet/): an id is claimed before its room opens and given back when it closes. */
export interface RoomDirectory {
  /** Resolves once this process holds `id`; rejects with a RoomError (a RoomMovedError when another server has it). */
  claim(id: string): Promise<void>;
  /** Gives back the claim on `id` (its room closed, or failed to open). */
  release(id: string): void;
  /** Rejects with a RoomMovedError when another server hosts `id`; resolves when none does. */
  locate(id: string): Promise<void>;
  /** The room `id` (claimed before) is open now: the fleet may list it. */
  opened(id: string): void;
}

/** Opens rooms somewhere other than this thread (the room workers); throws RoomError when it cannot. */
export interface RoomHost {
  open(spec: RoomSpec): Promise<HostedRoom>;
}

/** Options of RoomManager. */
export interface RoomManagerOptions {
  clock: Clock;
  metrics: ServerMetrics;
  logger: Logger;
  factory: RoomFactory;
  defaultScenario: string;
  defaultParams?: Readonly<Record<string, number>>;
  /** Seed of every room's simulation. Default 1. */
  seed?: number | string;
  snapshotRateHz: number;
  maxClientsPerRoom: number;
  /** Most rooms open at once (each has its own Jolt world in the shared 128 MB heap). Default 6. */
  maxRooms?: number;
  /** How long a non-default room may stay empty before it closes. Default 30 s. */
  emptyRoomGraceMs?: number;
  /** Passed to each room. */
  maxCatchUpTicks?: number;
  maxInputLeadTicks?: number;
  pauseWhenEmpty?: boolean;
  /** The catch-up budget rooms opened on this thread share. Default none. */
  catchUp?: CatchUpGate | null;
  /** The tick phases rooms opened on this thread spread over. Default none (each ticks from when it starts). */
  phases?: TickPhases | null;
  /** Net mode of rooms not asked for one ('auto': predict where the cost estimate allows). Default 'auto'. */
  netMode?: NetModeRequest;
  /** Where rooms are opened; default: on this thread through `factory`. */
  host?: RoomHost | null;
  /** With a fleet: where room ids are claimed fleet-wide (the default room is each process's own, never claimed). */
  directory?: RoomDirectory;
}

/** Where a client wants to go: an existing room by id, a new room from a scenario, or the default room. */
export interface RoomRequest {
  roomId?: string;
  scenario?: string;
  params?: Readonly<Record<string, number>>;
  /** Net mode of a room this request opens (default: the server's). */
  netMode?: NetModeRequest;
}

/** Owns every room of the process. */
export class RoomManager {
  private readonly opts: RoomManagerOptions;
  private readonly rooms = new Map<string, HostedRoom>();
  private readonly creating = new Map<string, Promise<HostedRoom>>();
  private readonly emptyTimers = new Map<string, TimerHandle>();
  private readonly openedListeners = new Set<(room: HostedRoom) => void>();
  private nextRoomNumber = 1;
  private closing = false;

  constructor(opts: RoomManagerOptions) {
    this.opts = opts;
  }

  /** Creates the default room. */
  async start(): Promise<HostedRoom> {
    return this.create(DEFAULT_ROOM_ID, this.opts.defaultScenario, this.opts.defaultParams ?? {});
  }

  /** Calls `fn` with every room that opens from now on (the Agones lifecycle watches players through it). */
  onRoomOpened(fn: (room: HostedRoom) => void): () => void {
    this.openedListeners.add(fn);
    return () => this.openedListeners.delete(fn);
  }

  /** The room with this id, if open. */
  get(id: string): HostedRoom | undefined {
    return this.rooms.get(id);
  }

  /** The room with this id when it runs on this thread (tests, bench and tools that reach into a room). */
  local(id: string): Room | undefined {
    const room = this.rooms.get(id);
    return room instanceof Room ? room : undefined;
  }

  /** Every open room that runs on this thread, in all() order. */
  localRooms(): Room[] {
    return this.all().filter((r): r is Room => r instanceof Room);
  }

  /** Every open room, default first, then by id. */
  all(): HostedRoom[] {
    return [...this.rooms.values()].sort((a, b) => (a.id === DEFAULT_ROOM_ID ? -1 : b.id === DEFAULT_ROOM_ID ? 1 : a.id < b.id ? -1 : a.id > b.id ? 1 : 0));
  }

  /** Summaries of every open room. */
  list(): RoomInfo[] {
    return this.all().map((r) => r.info());
  }

  /** Total members over all rooms. */
  clientCount(): number {
    let n = 0;
    for (const r of this.rooms.values()) n += r.clientCount;
    return n;
  }

  /**
   * Resolves a request to a room: an existing id; a new room under that id when a scenario is given too (or the id
   * itself names a scenario); a new room with a fresh id from a scenario alone; otherwise the default room.
   * Throws RoomError when it cannot.
   */
  async resolve(req: RoomRequest): Promise<HostedRoom> {
    if (this.closing) throw new RoomError(ErrorCode.Internal, 'the server is shutting down');
    if (req.roomId !== undefined) {
      if (!ROOM_ID_RE.test(req.roomId)) throw new RoomError(ErrorCode.BadMessage, `room id must match ${ROOM_ID_RE}, got ${JSON.stringify(req.roomId)}`);
      const existing = this.rooms.get(req.roomId);
      if (existing) {
        if (req.scenario !== undefined && req.scenario !== existing.scenarioName) {
          throw new RoomError(ErrorCode.BadMessage, `room ${req.roomId} runs scenario ${existing.scenarioName}, not ${req.scenario}`);
        }
        return existing;
      }
      const pending = this.creating.get(req.roomId);
      if (pending) return pending;
      if (this.opts.directory && req.roomId !== DEFAULT_ROOM_ID) await this.opts.directory.locate(req.roomId);
      // A room id that names a scenario opens a room of that scenario on demand (hello carries only a room id).
      const scenario = req.scenario ?? (this.opts.factory.hasScenario(req.roomId) ? req.roomId : undefined);
      if (scenario === undefined) {
        throw new RoomError(ErrorCode.RoomNotFound, `no room "${req.roomId}" (open rooms: ${this.all().map((r) => r.id).join(', ') || 'none'}; a scenario name opens a room of it)`);
      }
      return this.create(req.roomId, scenario, req.params ?? {}, req.netMode);
    }
    if (req.scenario !== undefined) {
      // With a fleet another server may hold the next number already: its claim refuses ours, so try the next.
      for (let attempt = 0; ; attempt++) {
        let id: string;
        do id = `${req.scenario}-${this.nextRoomNumber++}`.slice(0, 64);
        while (this.rooms.has(id) || this.creating.has(id));
        try {
          return await this.create(id, req.scenario, req.params ?? {}, req.netMode);
        } catch (error) {
          if (!(error instanceof RoomError && error.code === ErrorCode.RoomMoved) || attempt >= 20) throw error;
        }
      }
    }
    const def = this.rooms.get(DEFAULT_ROOM_ID);
    if (!def) throw new RoomError(ErrorCode.RoomNotFound, 'the default room is not open');
    return def;
  }

  /** Creates a room (shared by concurrent requests for the same id). Throws RoomError for limits and bad scenarios. */
  create(id: string, scenario: string, params: Readonly<Record<string, number>>, netMode?: NetModeRequest): Promise<HostedRoom> {
    if (this.closing) return Promise.reject(new RoomError(ErrorCode.Internal, 'the server is shutting down'));
    const existing = this.rooms.get(id);
    if (existing) return Promise.resolve(existing);
    const pending = this.creating.get(id);
    if (pending) return pending;
    const maxRooms = this.opts.maxRooms ?? 6;
    if (this.rooms.size + this.creating.size >= maxRooms) {
      return Promise.reject(new RoomError(ErrorCode.ServerFull, `the server already runs its limit of ${maxRooms} rooms`));
    }
    if (!this.opts.factory.hasScenario(scenario)) return Promise.reject(new RoomError(ErrorCode.BadMessage, `unknown scenario "${scenario}"`));
    const promise = this.build({ id, scenario, params, seed: this.opts.seed ?? 1, netMode: netMode ?? this.opts.netMode ?? 'auto' }).finally(() => this.creating.delete(id));
    this.creating.set(id, promise);
    return promise;
  }

  private async build(spec: RoomSpec): Promise<HostedRoom> {
    const directory = spec.id === DEFAULT_ROOM_ID ? undefined : this.opts.directory;
    if (!directory) return this.buildClaimed(spec);
    await directory.claim(spec.id);
    try {
      const room = await this.buildClaimed(spec);
      room.onClose(() => directory.release(spec.id));
      directory.opened(spec.id);
      return room;
    } catch (error) {
      directory.release(spec.id);
      throw error;
    }
  }

  private async buildClaimed(spec: RoomSpec): Promise<HostedRoom> {
    const room = this.opts.host ? await this.opts.host.open(spec) : await openRoom(spec, this.opts);
    return this.register(room);
  }

  /**
   * Opens a room around a simulation that already ran (a log resumed after a crash, server/resume-rooms.ts) under
   * its old id, on this thread; `prepare` runs before its first tick (it restores the held players). Throws RoomError
   * when the id is taken or the server is closing. `predictInputs` (the players in the game and their last commands)
   * lets predict mode's record stream go on; without them the room serves snapshots.
   */
  adopt(spec: RoomSpec, built: RoomSimulationBuild, recorder: RoomRecorder | null, prepare: (room: Room) => void, predictInputs: readonly PlayerInputState[] | null): Room {
    if (this.closing) throw new RoomError(ErrorCode.Internal, 'the server is shutting down');
    if (this.rooms.has(spec.id) || this.creating.has(spec.id)) throw new RoomError(ErrorCode.Internal, `room ${spec.id} is already open`);
    const netMode = predictInputs === null ? NetMode.Snapshot : (spec.netMode ?? this.opts.netMode ?? 'auto');
    const room = roomAround({ ...spec, netMode }, built, recorder, this.opts, predictInputs ?? undefined);
    const directory = spec.id === DEFAULT_ROOM_ID ? undefined : this.opts.directory;
    if (directory) {
      // A resumed room takes its id back in the fleet directory (it had it before the crash; its claim lapsed).
      directory.claim(spec.id).then(
        () => (room.closed ? directory.release(spec.id) : room.onClose(() => directory.release(spec.id))),
        (error: unknown) => this.opts.logger.error({ room: spec.id, err: error instanceof Error ? error.message : String(error) }, 'a resumed room could not take its id back in the fleet directory'),
      );
    }
    return this.register(room, () => prepare(room));
  }

  private register<T extends HostedRoom>(room: T, prepare?: () => void): T {
    const id = room.id;
    this.rooms.set(id, room);
    this.opts.metrics.rooms.set(this.rooms.size);
    room.onClose((reason) => {
      this.rooms.delete(id);
      this.clearEmptyTimer(id);
      this.opts.metrics.rooms.set(this.rooms.size);
      if (id === DEFAULT_ROOM_ID && this.opts.host) this.reopenDefault(reason);
    });
    if (id !== DEFAULT_ROOM_ID) {
      room.onEmptyChange((empty) => (empty ? this.armEmptyTimer(room) : this.clearEmptyTimer(id)));
      this.armEmptyTimer(room);
    }
    prepare?.();
    room.start();
    const info = room.info();
    this.opts.logger.info({ room: id, scenario: room.scenarioName, params: room.params, netMode: info.netMode, netModeNote: info.netModeNote }, 'room opened');
    for (const fn of this.openedListeners) fn(room);
    return room;
  }

  // The room that always exists lost its worker (or failed there): open it again, retrying while no worker can take it.
  private reopenDefault(reason: string, attempt = 1): void {
    if (this.closing) return;
    this.opts.logger.warn({ room: DEFAULT_ROOM_ID, reason, attempt }, 'the default room closed; opening it again');
    this.opts.clock.setTimer(Math.min(5000, 250 * attempt), () => {
      if (this.closing || this.rooms.has(DEFAULT_ROOM_ID) || this.creating.has(DEFAULT_ROOM_ID)) return;
      this.start().catch((error: unknown) => this.reopenDefault(error instanceof Error ? error.message : String(error), attempt + 1));
    });
  }

  private armEmptyTimer(room: HostedRoom): void {
    this.clearEmptyTimer(room.id);
    const graceMs = this.opts.emptyRoomGraceMs ?? 30_000;
    this.emptyTimers.set(
      room.id,
      this.opts.clock.setTimer(graceMs, () => {
        this.emptyTimers.delete(room.id);
        if (room.clientCount === 0) void room.close('room empty');
      }),
    );
  }

  private clearEmptyTimer(id: string): void {
    const t = this.emptyTimers.get(id);
    if (t) this.opts.clock.clearTimer(t);
    this.emptyTimers.delete(id);
  }

  /** Closes every room (members are told `reason`) and refuses new ones. */
  async closeAll(reason: string): Promise<void> {
    this.closing = true;
    await Promise.allSettled([...this.creating.values()]);
    for (const id of [...this.emptyTimers.keys()]) this.clearEmptyTimer(id);
    await Promise.all([...this.rooms.values()].map((r) => r.close(reason)));
  }
}
