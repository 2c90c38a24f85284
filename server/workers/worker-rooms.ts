// Inside a room worker: the worker's rooms and their members, driven by ToWorker messages. Each member's bytes go into
// one ByteBatcher flushed once per turn of the worker's loop (after the rooms that were due have ticked), with the
// ticks they ran; every room's load is pushed every STATUS_INTERVAL_MS. Never touches a socket.
import { PerformanceObserver } from 'node:perf_hooks';
import { getHeapStatistics } from 'node:v8';
import { NetMode } from '../../shared/protocol/predict-messages.ts';
import type { NetModeRequest } from '../net-mode-policy.ts';
import type { Clock } from '../../shared/clock.ts';
import { ErrorCode } from '../../shared/protocol/opcodes.ts';
import { CatchUpBudget } from '../catch-up-budget.ts';
import { TickPhases, workerPhaseOffsetMs } from '../tick-phases.ts';
import { DeliveryKind, type MemberSink, type OfferTally, type Seat } from '../hosted-room.ts';
import { enterRoom, seatOf } from '../local-seat.ts';
import { DeliveringMember } from '../member-delivery.ts';
import { SnapshotEncoder } from '../../shared/protocol/index.ts';
import type { Simulation } from '../../shared/sim/simulation.ts';
import type { RecordingFactory } from '../room-factory.ts';
import type { Logger } from '../logger.ts';
import type { ServerMetrics } from '../metrics.ts';
import { openRoom, roomAround, type OpenRoomOptions } from '../open-room.ts';
import { RoomError, type Room } from '../room.ts';
import type { RoomFactory, RoomSimulationBuild } from '../room-manager.ts';
import { OVERLOADED_NICENESS, setThreadNiceness } from './thread-priority.ts';
import { ByteBatcher, GC_PAUSE_FIELDS, STATUS_INTERVAL_MS, type CarriedMember, type FromWorker, type MovingRoom, type OpenedRoom, type RoomStatus, type ToWorker, type WorkerRoomConfig } from './worker-protocol.ts';

/** Where the worker's input offers are tallied: nobody reads it (the main thread's sessions count what they can see). */
const untallied: OfferTally = { inputsLate: 0, inputsTooFar: 0 };

/** Most GC pauses one status carries (a worker collecting more often than this is reported by its tick times). */
const MAX_GC_PAUSES_PER_STATUS = 256;

/** How a worker posts to the main thread (`transfer`: buffers whose ownership moves with the message). */
export type PostToMain = (msg: FromWorker, transfer?: ArrayBuffer[]) => void;

/** Options of WorkerRooms. */
export interface WorkerRoomsOptions {
  factory: RoomFactory & RecordingFactory;
  clock: Clock;
  metrics: ServerMetrics;
  logger: Logger;
  config: WorkerRoomConfig;
  post: PostToMain;
  /** This worker's place in the pool (its rooms' tick phases start at an offset from the other workers'). */
  worker?: { index: number; count: number };
}

/** A member seen from the worker: its bytes are batched for the main thread, which owns its socket. */
class RemoteSink implements MemberSink {
  /** The main thread said the member's socket is backed up. */
  backed = false;
  private readonly member: number;
  private readonly host: WorkerRooms;

  constructor(member: number, host: WorkerRooms) {
    this.member = member;
    this.host = host;
  }

  deliver(bytes: Uint8Array, kind: DeliveryKind): void {
    this.host.queue(this.member, bytes, kind);
  }
  snapshotSkipped(): void {}
  backedUp(): boolean {
    return this.backed;
  }
  // The main thread checks its socket on every delivery and disconnects a member too far behind.
  tooFarBehind(): boolean {
    return false;
  }
  roomClosed(reason: string): void {
    this.host.gone(this.member, true, reason);
  }
  removed(reason: string): void {
    this.host.gone(this.member, false, reason);
  }
}

interface MemberEntry {
  room: Room;
  seat: Omit<Seat, 'welcome'>;
  sink: RemoteSink;
  delivering: DeliveringMember;
}

/** One room's counters at the start of the current status window. */
interface Window {
  ticks: number;
  cpuSeconds: number;
  skipped: number;
  cpuMs: number | null;
}

/** The rooms of one worker. */
export class WorkerRooms {
  private readonly opts: WorkerRoomsOptions;
  private readonly rooms = new Map<string, Room>();
  private readonly members = new Map<number, MemberEntry>();
  private readonly windows = new Map<string, Window>();
  /** Simulations built for rooms about to move in, by room id. */
  private readonly prepared = new Map<string, Promise<RoomSimulationBuild & { sim: Simulation }>>();
  private readonly out = new ByteBatcher();
  private readonly ticks = new Map<string, number>();
  private flushPending = false;
  private readonly statusTimer: ReturnType<typeof setInterval>;
  private readonly catchUp = new CatchUpBudget();
  private readonly phases: TickPhases;
  private overloaded = false;
  /** GC pauses since the last status (GC_PAUSE_FIELDS numbers each); a worker's pauses stall only its own rooms. */
  private gcPauses: number[] = [];
  private readonly gcObserver = new PerformanceObserver((list) => {
    for (const e of list.getEntries()) {
      if (this.gcPauses.length < MAX_GC_PAUSES_PER_STATUS * GC_PAUSE_FIELDS) this.gcPauses.push(performance.timeOrigin + e.startTime, e.duration, (e as PerformanceEntry & { detail?: { kind?: number } }).detail?.kind ?? 0);
    }
  });

  constructor(opts: WorkerRoomsOptions) {
    this.opts = opts;
    this.phases = new TickPhases(undefined, opts.worker ? workerPhaseOffsetMs(opts.worker.index, opts.worker.count) : 0);
    this.gcObserver.observe({ entryTypes: ['gc'] });
    this.statusTimer = setInterval(() => this.pushStatus(), STATUS_INTERVAL_MS);
    this.statusTimer.unref();
  }

  /** Takes one message from the main thread; a failure answers the request (or is logged), never kills the worker. */
  handle(msg: ToWorker): void {
    try {
      this.dispatch(msg);
    } catch (error) {
      if ('req' in msg) this.fail(msg.req, error);
      else this.opts.logger.error({ err: error, message: msg.t }, 'room worker: handling a message failed');
    }
  }

  /** Queues one member's bytes for the next flush (RemoteSink). */
  queue(member: number, bytes: Uint8Array, kind: DeliveryKind): void {
    this.out.add(member, bytes, kind);
    this.scheduleFlush();
  }

  /** The room let go of a member (RemoteSink): the main thread hears it after the member's last bytes. */
  gone(member: number, closed: boolean, reason: string): void {
    this.members.delete(member);
    this.postInOrder({ t: 'gone', member, closed, reason });
  }

  private dispatch(msg: ToWorker): void {
    switch (msg.t) {
      case 'open':
        void this.open(msg.req, msg.id, msg.scenario, msg.params, msg.seed, msg.netMode);
        return;
      case 'enter': {
        const room = this.rooms.get(msg.room);
        if (!room || room.closed) throw new RoomError(ErrorCode.RoomNotFound, `room ${msg.room} is closed`);
        const sink = new RemoteSink(msg.member, this);
        const seat = enterRoom(room, sink, msg.entry, this.opts.metrics);
        this.members.set(msg.member, { room, seat, sink, delivering: seat.member });
        this.reply(msg.req, { playerId: seat.playerId, welcome: seat.welcome });
        return;
      }
      case 'leave':
        this.dropMember(msg.room, msg.player);
        this.rooms.get(msg.room)?.leave(msg.player);
        return;
      case 'detach':
        this.dropMember(msg.room, msg.player);
        this.rooms.get(msg.room)?.detach(msg.player);
        return;
      case 'close': {
        const room = this.rooms.get(msg.room);
        if (!room) {
          this.reply(msg.req, null);
          return;
        }
        void room.close(msg.reason).then(
          () => this.reply(msg.req, null),
          (error: unknown) => this.fail(msg.req, error),
        );
        return;
      }
      case 'traffic': {
        const { inputs, messages, acks, pressure, netModes } = msg.traffic;
        for (const input of inputs) {
          const m = this.members.get(input.member);
          if (m) m.seat.offerInputs(input.firstTick, input.commands, untallied);
        }
        for (const g of messages) this.members.get(g.member)?.seat.offerMessage(g.name, g.payload, g.tick);
        for (let i = 0; i < acks.length; i += 2) this.members.get(acks[i])?.seat.acknowledge(acks[i + 1]);
        for (let i = 0; i < pressure.length; i += 2) {
          const m = this.members.get(pressure[i]);
          if (m) m.sink.backed = pressure[i + 1] === 1;
        }
        for (let i = 0; i < netModes.length; i += 2) this.members.get(netModes[i])?.seat.setNetMode(netModes[i + 1] === 1 ? NetMode.Predict : NetMode.Snapshot);
        return;
      }
      case 'prepare': {
        const factory: RecordingFactory = this.opts.factory;
        const built = factory.createSimulation(msg.scenario, msg.params, msg.seed);
        void this.prepared.get(msg.room)?.then((b) => b.sim.destroy(), () => undefined);
        this.prepared.set(msg.room, built);
        built.then(
          () => this.reply(msg.req, null),
          (error: unknown) => {
            if (this.prepared.get(msg.room) === built) this.prepared.delete(msg.room);
            this.fail(msg.req, error);
          },
        );
        return;
      }
      case 'discard': {
        const built = this.prepared.get(msg.room);
        this.prepared.delete(msg.room);
        void built?.then((b) => b.sim.destroy(), () => undefined);
        return;
      }
      case 'export':
        void this.exportRoom(msg.req, msg.room);
        return;
      case 'import':
        void this.importRoom(msg.req, msg.moving);
        return;
      case 'metrics':
        void this.opts.metrics.registry.getMetricsAsJSON().then(
          (json) => this.reply(msg.req, json),
          (error: unknown) => this.fail(msg.req, error),
        );
        return;
    }
  }

  private async open(req: number, id: string, scenario: string, params: Readonly<Record<string, number>>, seed: number | string, netMode: NetModeRequest | undefined): Promise<void> {
    try {
      if (this.rooms.has(id)) throw new RoomError(ErrorCode.Internal, `room ${id} is already open in this worker`);
      const room = await openRoom({ id, scenario, params, seed, netMode }, { factory: this.opts.factory, ...this.roomOptions() });
      this.host(room);
      room.start();
      this.reply(req, { info: room.info(), recordingPath: this.opts.factory.recordingPath(id) });
    } catch (error) {
      this.fail(req, error);
    }
  }

  private roomOptions(): Omit<OpenRoomOptions, 'factory'> {
    const { config } = this.opts;
    return {
      clock: this.opts.clock,
      metrics: this.opts.metrics,
      logger: this.opts.logger,
      snapshotRateHz: config.snapshotRateHz,
      maxClientsPerRoom: config.maxClientsPerRoom,
      maxCatchUpTicks: config.maxCatchUpTicks,
      maxInputLeadTicks: config.maxInputLeadTicks,
      pauseWhenEmpty: config.pauseWhenEmpty,
      catchUp: this.catchUp,
      phases: this.phases,
    };
  }

  private host(room: Room): void {
    const id = room.id;
    this.rooms.set(id, room);
    room.onTick(() => {
      this.ticks.set(id, room.sim.tick);
      this.scheduleFlush();
    });
    room.onClose((reason) => {
      this.forgetRoom(room);
      this.postInOrder({ t: 'closed', room: id, reason });
    });
  }

  private forgetRoom(room: Room): void {
    this.rooms.delete(room.id);
    this.windows.delete(room.id);
    this.ticks.delete(room.id);
    for (const [member, m] of this.members) if (m.room === room) this.members.delete(member);
  }

  // Stops the room between two ticks; every byte it sent goes out before the reply that hands it over.
  private async exportRoom(req: number, id: string): Promise<void> {
    try {
      const room = this.rooms.get(id);
      if (!room) throw new RoomError(ErrorCode.RoomNotFound, `room ${id} is not open in this worker`);
      const entries = [...this.members].filter(([, m]) => m.room === room);
      const carry = await room.handOff();
      const members: CarriedMember[] = entries.map(([member, m]) => ({ member, playerId: m.seat.playerId, predict: m.delivering.predictState }));
      this.forgetRoom(room);
      this.reply(req, { carry, members } satisfies MovingRoom);
    } catch (error) {
      this.fail(req, error);
    }
  }

  // Goes on with a room exported by another worker: the simulation from its checkpoint (checked against its hash), the
  // log appended to where it stopped, the members served from the next tick without a new welcome.
  private async importRoom(req: number, moving: MovingRoom): Promise<void> {
    const { carry } = moving;
    let built: (RoomSimulationBuild & { sim: Simulation }) | null = null;
    const ready = this.prepared.get(carry.id);
    this.prepared.delete(carry.id);
    try {
      const factory: RecordingFactory = this.opts.factory;
      const b = await (ready ?? factory.createSimulation(carry.scenario, carry.params, carry.seed));
      built = b;
      if (this.rooms.has(carry.id)) throw new RoomError(ErrorCode.Internal, `room ${carry.id} is already open in this worker`);
      b.sim.restoreCheckpointBytes(carry.checkpoint);
      if (b.sim.tick !== carry.tick || b.sim.stateHash() !== carry.hash) throw new Error(`room ${carry.id}: the restored checkpoint is at tick ${b.sim.tick} with hash ${b.sim.stateHash()}, expected tick ${carry.tick} with ${carry.hash}`);
      const spec = { id: carry.id, scenario: carry.scenario, params: carry.params, seed: carry.seed, netMode: carry.netModeRequested };
      const recorder = carry.log ? await factory.continueRecording({ ...spec, sim: b.sim }, carry.log) : null;
      const room = roomAround(spec, b, recorder, this.roomOptions(), carry.predictInputs ?? undefined, carry);
      built = null; // the room owns the simulation now
      for (const c of moving.members) {
        const sink = new RemoteSink(c.member, this);
        const delivering = new DeliveringMember(sink, room.snapshots, this.opts.metrics, room.predictFeed);
        delivering.encoder = new SnapshotEncoder(room.snapshots.format);
        delivering.continueStream(c.predict);
        if (room.reattach(c.playerId, delivering) === null) continue;
        this.members.set(c.member, { room, seat: seatOf(room, c.playerId, delivering), sink, delivering });
      }
      this.host(room);
      room.start();
      this.reply(req, { info: room.info(), recordingPath: factory.recordingPath(carry.id) } satisfies OpenedRoom);
    } catch (error) {
      built?.sim.destroy();
      this.fail(req, error);
    }
  }

  private dropMember(roomId: string, playerId: number): void {
    for (const [member, m] of this.members) if (m.room.id === roomId && m.seat.playerId === playerId) this.members.delete(member);
  }

  private reply(req: number, value: unknown): void {
    this.postInOrder({ t: 'reply', req, ok: true, value });
  }

  private fail(req: number, error: unknown): void {
    const code = error instanceof RoomError ? error.code : null;
    if (code === null) this.opts.logger.error({ err: error }, 'room worker: a request failed');
    this.postInOrder({ t: 'reply', req, ok: false, code, message: error instanceof Error ? error.message : String(error) });
  }

  /** Posts after every byte queued before it, so the main thread sees deliveries and notices in the order they happened. */
  private postInOrder(msg: FromWorker): void {
    this.flush();
    this.opts.post(msg);
  }

  private scheduleFlush(): void {
    if (this.flushPending) return;
    this.flushPending = true;
    setImmediate(() => this.flush());
  }

  private flush(): void {
    this.flushPending = false;
    if (this.out.empty && this.ticks.size === 0) return;
    const batch = this.out.take();
    const ticks = [...this.ticks];
    this.ticks.clear();
    this.opts.post({ t: 'out', batch, ticks }, [batch.buffer]);
  }

  private pushStatus(): void {
    const rooms: RoomStatus[] = [];
    for (const room of this.rooms.values()) rooms.push(this.status(room));
    this.adjustPriority(rooms);
    const gcPauses = this.gcPauses;
    this.gcPauses = [];
    this.opts.post({ t: 'status', rooms, externalBytes: getHeapStatistics().external_memory, gcPauses });
  }

  // Over budget, the worker's rooms cannot all keep 60 Hz: the worker yields the CPU to the main thread and the other
  // workers (its rooms slow down and say so) until its load fits again.
  private adjustPriority(rooms: readonly RoomStatus[]): void {
    let loadMs = 0;
    for (const r of rooms) loadMs += r.tickCpuMs ?? 0;
    const overloaded = loadMs > this.opts.config.budgetMsPerTick;
    if (overloaded === this.overloaded) return;
    this.overloaded = overloaded;
    const failed = setThreadNiceness(overloaded ? OVERLOADED_NICENESS : 0);
    if (failed !== null) this.opts.logger.warn({ loadMs, overloaded, reason: failed }, 'room worker could not change its thread priority');
    else this.opts.logger.info({ loadMs: Math.round(loadMs * 10) / 10, budgetMs: this.opts.config.budgetMsPerTick }, overloaded ? 'room worker over its CPU budget: running at the lowest priority' : 'room worker back within its CPU budget: normal priority');
  }

  private status(room: Room): RoomStatus {
    const clock = room.tickClock;
    const w = this.windows.get(room.id) ?? { ticks: clock.ticksRun, cpuSeconds: room.cpuSeconds, skipped: clock.skippedTicks, cpuMs: null };
    const ran = clock.ticksRun - w.ticks;
    const cpuMs = ran > 0 ? ((room.cpuSeconds - w.cpuSeconds) * 1000) / ran : w.cpuMs;
    this.windows.set(room.id, { ticks: clock.ticksRun, cpuSeconds: room.cpuSeconds, skipped: clock.skippedTicks, cpuMs });
    const missed: number[] = [];
    const info = room.info();
    for (const playerId of room.playerIds()) missed.push(playerId, room.missedInputTicks(playerId));
    return {
      id: room.id,
      tick: info.tick,
      clients: info.clients,
      bodies: info.bodies,
      heap: room.heapUsage(),
      ticksPerSecond: info.ticksPerSecond,
      tickCpuMs: cpuMs,
      slow: info.slow,
      tickMsP99: info.tickMsP99,
      tickCpuMsP99: info.tickCpuMsP99,
      tickGapMsMax: info.tickGapMsMax,
      skippedTicks: clock.skippedTicks,
      missedInputTicks: missed,
    };
  }

  /** Closes every room (the worker is being stopped). */
  async closeAll(reason: string): Promise<void> {
    clearInterval(this.statusTimer);
    this.gcObserver.disconnect();
    await Promise.all([...this.rooms.values()].map((r) => r.close(reason)));
    this.flush();
  }
}
