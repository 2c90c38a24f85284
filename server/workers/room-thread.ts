// One room worker seen from the main thread: starts the thread, answers its replies, hands each flush of member bytes
// to the members' sessions, batches members' inputs, acks and socket pressure into one message per turn, and when the
// thread dies closes only its rooms (their clients get a bye saying why) and logs it.
import { Worker } from 'node:worker_threads';
import type { InputCommand } from '../../shared/sim/input.ts';
import { ErrorCode } from '../../shared/protocol/opcodes.ts';
import { NetMode } from '../../shared/protocol/predict-messages.ts';
import type { MemberSink, RoomEntry } from '../hosted-room.ts';
import type { Logger } from '../logger.ts';
import { RoomError } from '../room.ts';
import type { RoomSpec } from '../room-manager.ts';
import { RemoteRoom, type RoomThreadLink } from './remote-room.ts';
import { forEachSend, GC_PAUSE_FIELDS, type EnteredRoom, type FromWorker, type MemberTraffic, type MovingRoom, type OpenedRoom, type ToWorker, type WorkerInit } from './worker-protocol.ts';
import { siblingModuleUrl } from '../package-root.ts';

/** GC pauses a RoomThread keeps of its worker. */
const RECENT_GC_PAUSES = 4096;

/** Members of every thread share one numbering (a member id is never reused in a process). */
let nextMemberId = 1;

/** Where a member's bytes go on this thread, and the room and player it is in. */
export interface MemberRoute {
  sink: MemberSink;
  room: RemoteRoom;
  playerId: number;
}

interface Pending {
  resolve(value: unknown): void;
  reject(error: Error): void;
}

const emptyTraffic = (): MemberTraffic => ({ inputs: [], messages: [], acks: [], pressure: [], netModes: [] });

/** A started room worker. */
export class RoomThread implements RoomThreadLink {
  readonly index: number;
  /** The thread itself (tests end it to check that a dead worker is handled). */
  readonly worker: Worker;
  /** Rooms open in this worker, by id. */
  readonly rooms = new Map<string, RemoteRoom>();
  /** The worker's external (WASM and buffer) memory as last reported. */
  externalBytes = 0;
  /** The worker's recent GC pauses, oldest first (the last RECENT_GC_PAUSES, GC_PAUSE_FIELDS numbers each). */
  readonly gcPauses: number[] = [];
  private readonly logger: Logger;
  private readonly onDied: (thread: RoomThread, why: string) => void;
  private readonly pending = new Map<number, Pending>();
  private readonly routes = new Map<number, MemberRoute>();
  private readonly backed = new Set<number>();
  private nextReq = 1;
  private traffic = emptyTraffic();
  private flushPending = false;
  private stopping = false;
  private deadReason: string | null = null;
  private readyWaiter: (() => void) | null = null;

  private constructor(init: WorkerInit, logger: Logger, onDied: (thread: RoomThread, why: string) => void, youngGenerationMb?: number) {
    this.index = init.index;
    this.logger = logger;
    this.onDied = onDied;
    const resourceLimits = youngGenerationMb === undefined ? undefined : { maxYoungGenerationSizeMb: youngGenerationMb };
    this.worker = new Worker(siblingModuleUrl(import.meta.url, 'room-worker'), { workerData: init, name: `room-worker-${init.index}`, resourceLimits });
    this.worker.on('message', (msg: FromWorker) => this.receive(msg));
    this.worker.on('error', (error) => this.died(`it threw ${error instanceof Error ? error.message : String(error)}`, error));
    this.worker.on('exit', (code) => this.died(`it exited with code ${code}`, null));
  }

  /** Starts a worker (with this young-generation size in MB, or V8's) and waits until it has loaded Jolt and its scenarios. */
  static start(init: WorkerInit, logger: Logger, onDied: (thread: RoomThread, why: string) => void, youngGenerationMb?: number): Promise<RoomThread> {
    return new Promise((resolve, reject) => {
      const thread = new RoomThread(
        init,
        logger,
        (t, why) => {
          reject(new Error(`room worker ${init.index} failed to start: ${why}`));
          onDied(t, why);
        },
        youngGenerationMb,
      );
      thread.readyWaiter = () => resolve(thread);
    });
  }

  /** Whether the thread has died. */
  get dead(): boolean {
    return this.deadReason !== null;
  }

  /** Opens a room in this worker. */
  async open(spec: RoomSpec): Promise<RemoteRoom> {
    const opened = (await this.request({ t: 'open', req: 0, ...spec })) as OpenedRoom;
    const room = new RemoteRoom(this, this.index, opened.info, spec.seed, opened.recordingPath);
    this.rooms.set(room.id, room);
    return room;
  }

  /** Stops a room of this worker between two ticks and takes it out, with its state and members (a room moving). */
  exportRoom(roomId: string): Promise<MovingRoom> {
    this.flushTraffic();
    return this.request({ t: 'export', req: 0, room: roomId }) as Promise<MovingRoom>;
  }

  /** Has the worker build a simulation for a room about to move in (before the room stops where it runs). */
  async prepareRoom(room: RemoteRoom): Promise<void> {
    await this.request({ t: 'prepare', req: 0, room: room.id, scenario: room.scenarioName, params: room.params, seed: room.seed });
  }

  /** Drops what prepareRoom built (the move did not happen). */
  discardPrepared(roomId: string): void {
    this.post({ t: 'discard', room: roomId });
  }

  /** Gives up a moved-out room and its members' routes (same member ids on the thread that adopts them). */
  releaseRoom(room: RemoteRoom): Array<[number, MemberRoute]> {
    this.rooms.delete(room.id);
    const out: Array<[number, MemberRoute]> = [];
    for (const [member, r] of this.routes) if (r.room === room) out.push([member, r]);
    for (const [member] of out) this.unroute(member);
    return out;
  }

  /** Takes a room moving in and its members' routes, then has the worker go on with it. */
  async importRoom(room: RemoteRoom, routes: ReadonlyArray<[number, MemberRoute]>, moving: MovingRoom): Promise<OpenedRoom> {
    for (const [member, r] of routes) this.routes.set(member, r);
    this.rooms.set(room.id, room);
    try {
      return (await this.request({ t: 'import', req: 0, moving })) as OpenedRoom;
    } catch (error) {
      if (this.rooms.get(room.id) === room) this.releaseRoom(room);
      throw error;
    }
  }

  /** The worker's metrics as prom-client JSON (null when it does not answer within `timeoutMs`). */
  metricsJson(timeoutMs: number): Promise<unknown> {
    if (this.dead) return Promise.resolve(null);
    const timeout = new Promise<null>((resolve) => setTimeout(() => resolve(null), timeoutMs).unref());
    return Promise.race([this.request({ t: 'metrics', req: 0 }).catch(() => null), timeout]);
  }

  /** Ends the thread (the server is stopping; its rooms were closed first). */
  async stop(): Promise<void> {
    this.stopping = true;
    await this.worker.terminate();
  }

  route(sink: MemberSink, room: RemoteRoom): number {
    const member = nextMemberId++;
    this.routes.set(member, { sink, room, playerId: 0 });
    return member;
  }

  seated(member: number, playerId: number): void {
    const r = this.routes.get(member);
    if (r) r.playerId = playerId;
  }

  unroute(member: number): void {
    this.routes.delete(member);
    this.backed.delete(member);
  }

  enter(room: string, member: number, entry: RoomEntry): Promise<EnteredRoom> {
    return this.request({ t: 'enter', req: 0, room, member, entry }) as Promise<EnteredRoom>;
  }

  leave(room: string, player: number): void {
    this.post({ t: 'leave', room, player });
  }

  detach(room: string, player: number): void {
    this.post({ t: 'detach', room, player });
  }

  async close(room: string, reason: string): Promise<void> {
    await this.request({ t: 'close', req: 0, room, reason });
  }

  queueInput(member: number, tick: number, command: InputCommand): void {
    const last = this.traffic.inputs.at(-1);
    if (last && last.member === member && last.firstTick + last.commands.length === tick) last.commands.push(command);
    else this.traffic.inputs.push({ member, firstTick: tick, commands: [command] });
    this.scheduleFlush();
  }

  queueMessage(member: number, name: string, payload: readonly number[], tick?: number): void {
    this.traffic.messages.push(tick === undefined ? { member, name, payload: [...payload] } : { member, name, payload: [...payload], tick });
    this.scheduleFlush();
  }

  queueAck(member: number, tick: number): void {
    this.traffic.acks.push(member, tick);
    this.scheduleFlush();
  }

  queueNetMode(member: number, mode: NetMode): void {
    this.traffic.netModes.push(member, mode === NetMode.Predict ? 1 : 0);
    this.scheduleFlush();
  }

  private request(msg: Extract<ToWorker, { req: number }>): Promise<unknown> {
    if (this.deadReason !== null) return Promise.reject(new RoomError(ErrorCode.Internal, `room worker ${this.index} has stopped: ${this.deadReason}`));
    const req = this.nextReq++;
    return new Promise((resolve, reject) => {
      this.pending.set(req, { resolve, reject });
      this.post({ ...msg, req } as ToWorker);
    });
  }

  private post(msg: ToWorker): void {
    if (this.deadReason === null) this.worker.postMessage(msg);
  }

  private scheduleFlush(): void {
    if (this.flushPending) return;
    this.flushPending = true;
    setImmediate(() => this.flushTraffic());
  }

  /** Posts what members queued now (a room about to move: nothing of it may trail behind its export). */
  flushTraffic(): void {
    this.flushPending = false;
    const traffic = this.traffic;
    this.traffic = emptyTraffic();
    if (traffic.inputs.length + traffic.messages.length + traffic.acks.length + traffic.pressure.length + traffic.netModes.length > 0) this.post({ t: 'traffic', traffic });
  }

  private receive(msg: FromWorker): void {
    switch (msg.t) {
      case 'ready':
        this.readyWaiter?.();
        this.readyWaiter = null;
        return;
      case 'reply': {
        const p = this.pending.get(msg.req);
        if (!p) return;
        this.pending.delete(msg.req);
        if (msg.ok) p.resolve(msg.value);
        else p.reject(new RoomError(msg.code ?? ErrorCode.Internal, msg.message));
        return;
      }
      case 'out':
        for (const [id, tick] of msg.ticks) this.rooms.get(id)?.ticked(tick);
        this.deliver(msg);
        return;
      case 'gone': {
        const r = this.routes.get(msg.member);
        if (!r) return;
        this.unroute(msg.member);
        if (msg.closed) {
          r.sink.roomClosed(msg.reason);
        } else {
          r.room.removedPlayer(r.playerId);
          r.sink.removed(msg.reason);
        }
        return;
      }
      case 'closed': {
        const room = this.rooms.get(msg.room);
        if (!room) return;
        this.rooms.delete(msg.room);
        room.closedBy(msg.reason, this.takeRoutes(room));
        return;
      }
      case 'log':
        this.relayLog(msg.line);
        return;
      case 'status':
        this.externalBytes = msg.externalBytes;
        this.gcPauses.push(...msg.gcPauses);
        if (this.gcPauses.length > RECENT_GC_PAUSES * GC_PAUSE_FIELDS) this.gcPauses.splice(0, this.gcPauses.length - RECENT_GC_PAUSES * GC_PAUSE_FIELDS);
        for (const s of msg.rooms) this.rooms.get(s.id)?.reported(s);
        return;
    }
  }

  private relayLog(line: string): void {
    try {
      const { level, msg, time: _time, pid: _pid, hostname: _hostname, ...fields } = JSON.parse(line) as Record<string, unknown>;
      const name = typeof level === 'number' ? this.logger.levels.labels[level] : undefined;
      const log = name === 'fatal' || name === 'error' || name === 'warn' || name === 'info' || name === 'debug' || name === 'trace' ? name : 'info';
      this.logger[log](fields, typeof msg === 'string' ? msg : '');
    } catch {
      this.logger.warn({ worker: this.index, line: line.slice(0, 200) }, 'room worker wrote an unreadable log line');
    }
  }

  private deliver(msg: Extract<FromWorker, { t: 'out' }>): void {
    const touched = new Set<number>(this.backed);
    forEachSend(msg.batch, (member, bytes, kind) => {
      const r = this.routes.get(member);
      if (!r || r.sink.tooFarBehind()) return;
      r.sink.deliver(bytes, kind);
      touched.add(member);
    });
    // Snapshots for a backed-up socket are skipped in the worker; it hears when the socket drains (or backs up).
    for (const member of touched) {
      const r = this.routes.get(member);
      if (!r) {
        this.backed.delete(member);
        continue;
      }
      const now = r.sink.backedUp();
      if (now === this.backed.has(member)) continue;
      if (now) this.backed.add(member);
      else this.backed.delete(member);
      this.traffic.pressure.push(member, now ? 1 : 0);
      this.scheduleFlush();
    }
  }

  private takeRoutes(room: RemoteRoom): MemberSink[] {
    const sinks: MemberSink[] = [];
    for (const [member, r] of this.routes) {
      if (r.room !== room) continue;
      sinks.push(r.sink);
      this.unroute(member);
    }
    return sinks;
  }

  private died(why: string, error: unknown): void {
    if (this.deadReason !== null) return;
    this.deadReason = why;
    if (this.stopping) return;
    this.logger.error({ worker: this.index, err: error, rooms: [...this.rooms.keys()] }, `room worker ${this.index} died (${why}); closing its rooms`);
    for (const p of this.pending.values()) p.reject(new RoomError(ErrorCode.Internal, `room worker ${this.index} stopped: ${why}`));
    this.pending.clear();
    const reason = `room error: the room's worker thread stopped (${why})`;
    for (const room of [...this.rooms.values()]) room.closedBy(reason, this.takeRoutes(room));
    this.rooms.clear();
    this.onDied(this, why);
  }
}
