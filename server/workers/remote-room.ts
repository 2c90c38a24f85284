// A room that runs in a room worker, as the main thread sees it: the players it holds (mirrored from joins, leaves and
// the worker's notices), its last reported tick and load, and seats whose inputs and acks travel to the worker in the
// thread's next traffic flush.
import type { InputCommand } from '../../shared/sim/input.ts';
import type { NetMode } from '../../shared/protocol/predict-messages.ts';
import type { HostedRoom, MemberSink, RoomEntry, Seat } from '../hosted-room.ts';
import type { RoomInfo } from '../room.ts';
import type { EnteredRoom, RoomStatus } from './worker-protocol.ts';

/** What a RemoteRoom needs from the thread its room runs on. */
export interface RoomThreadLink {
  /** Routes a member's bytes to `sink`; returns the member id the worker will know it by. */
  route(sink: MemberSink, room: RemoteRoom): number;
  /** Records the player a routed member took (the worker's notices name members). */
  seated(member: number, playerId: number): void;
  unroute(member: number): void;
  enter(room: string, member: number, entry: RoomEntry): Promise<EnteredRoom>;
  leave(room: string, playerId: number): void;
  detach(room: string, playerId: number): void;
  close(room: string, reason: string): Promise<void>;
  queueInput(member: number, tick: number, command: InputCommand): void;
  queueMessage(member: number, name: string, payload: readonly number[], tick?: number): void;
  queueAck(member: number, tick: number): void;
  /** Serve the member in predict mode (again: a resync) or on snapshots. */
  queueNetMode(member: number, mode: NetMode): void;
}

/** One move of a room between workers (/api/rooms, logs). */
export interface RoomMoveSummary {
  from: number;
  to: number;
  /** The tick it stopped at in the old worker and went on from in the new one. */
  tick: number;
  /** How long its players saw no tick (ms). */
  pauseMs: number;
  reason: string;
}

/** A room hosted by a worker thread. */
export class RemoteRoom implements HostedRoom {
  readonly id: string;
  readonly scenarioName: string;
  readonly params: Readonly<Record<string, number>>;
  readonly seed: number | string;
  /** The index in the pool of the worker it runs in (changes when it moves). */
  workerIndex: number;
  /** Times it moved to another worker, and the last move. */
  moves = 0;
  lastMove: RoomMoveSummary | null = null;
  private thread: RoomThreadLink;
  /** While the room moves between workers: what its players did meanwhile, for the worker it lands in. */
  private held: Array<(thread: RoomThreadLink) => void> | null = null;
  private moved: { done: Promise<void>; resolve: () => void } | null = null;
  /** Players by id, with the member id of their live link (null: held for a reconnect). */
  private readonly players = new Map<number, number | null>();
  private readonly closeListeners = new Set<(reason: string) => void>();
  private readonly emptyListeners = new Set<(empty: boolean) => void>();
  private closedReason: string | null = null;
  private lastTick: number;
  private lastStatus: RoomStatus | null = null;
  private readonly opened: RoomInfo;

  readonly recordingPath: string | null;

  constructor(thread: RoomThreadLink, workerIndex: number, opened: RoomInfo, seed: number | string, recordingPath: string | null = null) {
    this.seed = seed;
    this.recordingPath = recordingPath;
    this.thread = thread;
    this.workerIndex = workerIndex;
    this.id = opened.id;
    this.scenarioName = opened.scenario;
    this.params = opened.params;
    this.opened = opened;
    this.lastTick = opened.tick;
  }

  get closed(): boolean {
    return this.closedReason !== null;
  }

  get clientCount(): number {
    return this.players.size;
  }

  /** The worker's latest figures for this room (null before the first report). */
  get status(): RoomStatus | null {
    return this.lastStatus;
  }

  info(): RoomInfo {
    const s = this.lastStatus;
    return {
      ...this.opened,
      clients: this.players.size,
      tick: this.lastTick,
      bodies: s ? s.bodies : this.opened.bodies,
      ticksPerSecond: s ? s.ticksPerSecond : this.opened.ticksPerSecond,
      slow: s ? s.slow : this.opened.slow,
      tickMsP99: s ? s.tickMsP99 : this.opened.tickMsP99,
      tickCpuMsP99: s ? s.tickCpuMsP99 : this.opened.tickCpuMsP99,
      tickGapMsMax: s ? s.tickGapMsMax : this.opened.tickGapMsMax,
      worker: this.workerIndex,
      moves: this.moves,
    };
  }

  heapUsage(): { usedBytes: number; freeBytes: number } | null {
    return this.closed ? null : (this.lastStatus?.heap ?? null);
  }

  hasPlayer(playerId: number): boolean {
    return this.players.has(playerId);
  }

  detach(playerId: number): boolean {
    const member = this.players.get(playerId);
    if (member === undefined || member === null || this.closed) return false;
    this.players.set(playerId, null);
    this.via((t) => {
      t.unroute(member);
      t.detach(this.id, playerId);
    });
    return true;
  }

  leave(playerId: number): void {
    if (!this.players.has(playerId)) return;
    this.forget(playerId);
    if (!this.closed) this.via((t) => t.leave(this.id, playerId));
  }

  /** Holds what players do from now until endMove() (the room is being exported from its worker). */
  beginMove(): void {
    this.held = [];
    let resolve = (): void => undefined;
    const done = new Promise<void>((r) => (resolve = r));
    this.moved = { done, resolve };
  }

  /** The room now runs on `thread` (or still on the old one when the move failed): what was held goes there. */
  endMove(thread: RoomThreadLink, workerIndex: number, summary: RoomMoveSummary | null): void {
    this.thread = thread;
    this.workerIndex = workerIndex;
    if (summary) {
      this.moves++;
      this.lastMove = summary;
    }
    const held = this.held ?? [];
    const moved = this.moved;
    this.held = null;
    this.moved = null;
    if (!this.closed) for (const fn of held) fn(thread);
    moved?.resolve();
  }

  async enter(sink: MemberSink, entry: RoomEntry): Promise<Seat> {
    while (this.moved) await this.moved.done;
    const member = this.thread.route(sink, this);
    let entered: EnteredRoom;
    try {
      entered = await this.thread.enter(this.id, member, entry);
    } catch (error) {
      this.via((t) => t.unroute(member));
      throw error;
    }
    const { playerId } = entered;
    // A move may have begun while the worker seated the member: its route travels with the room.
    this.via((t) => t.seated(member, playerId));
    const wasEmpty = this.players.size === 0;
    this.players.set(playerId, member);
    if (wasEmpty) this.emptyListeners.forEach((fn) => fn(false));
    return {
      playerId,
      welcome: entered.welcome,
      offerInput: (tick, command) => {
        this.via((t) => t.queueInput(member, tick, command));
        return null;
      },
      offerInputs: (firstTick, commands) => {
        for (let i = 0; i < commands.length; i++) this.via((t) => t.queueInput(member, firstTick + i, commands[i]));
      },
      offerMessage: (name, payload, tick) => {
        this.via((t) => t.queueMessage(member, name, payload, tick));
        return null;
      },
      acknowledge: (tick) => this.via((t) => t.queueAck(member, tick)),
      pace: () => ({ ticksPerSecond: this.lastStatus?.ticksPerSecond ?? 0, slow: this.lastStatus?.slow ?? false }),
      setNetMode: (mode) => this.via((t) => t.queueNetMode(member, mode)),
      serverTick: () => this.lastTick,
      missedInputTicks: () => {
        const missed = this.lastStatus?.missedInputTicks ?? [];
        for (let i = 0; i < missed.length; i += 2) if (missed[i] === playerId) return missed[i + 1];
        return 0;
      },
    };
  }

  onClose(fn: (reason: string) => void): () => void {
    this.closeListeners.add(fn);
    return () => this.closeListeners.delete(fn);
  }

  onEmptyChange(fn: (empty: boolean) => void): () => void {
    this.emptyListeners.add(fn);
    return () => this.emptyListeners.delete(fn);
  }

  /** The worker started the room when it opened it. */
  start(): void {}

  async close(reason: string): Promise<void> {
    while (this.moved) await this.moved.done;
    if (this.closed) return;
    try {
      await this.thread.close(this.id, reason);
    } catch (error) {
      if (!this.closed) throw error; // its worker died meanwhile: the room is closed all the same
    }
  }

  /** The worker ran ticks up to `tick` (from its byte batches). */
  ticked(tick: number): void {
    this.lastTick = tick;
  }

  /** The worker's periodic figures. */
  reported(status: RoomStatus): void {
    this.lastStatus = status;
    this.lastTick = Math.max(this.lastTick, status.tick);
  }

  /** The worker removed a player (its delivery failed). */
  removedPlayer(playerId: number): void {
    this.forget(playerId);
  }

  /** The room is gone (closed in its worker, or the worker died): members still routed are told why. */
  closedBy(reason: string, members: Iterable<MemberSink>): void {
    if (this.closed) return;
    this.closedReason = reason;
    this.players.clear();
    for (const sink of members) {
      try {
        sink.roomClosed(reason);
      } catch {
        // the session is gone already
      }
    }
    for (const fn of this.closeListeners) fn(reason);
    this.closeListeners.clear();
    this.emptyListeners.clear();
  }

  // Straight to the worker, or held for the one the room lands in while it moves.
  private via(fn: (thread: RoomThreadLink) => void): void {
    if (this.held) this.held.push(fn);
    else fn(this.thread);
  }

  private forget(playerId: number): void {
    const member = this.players.get(playerId);
    if (member !== undefined && member !== null) this.via((t) => t.unroute(member));
    this.players.delete(playerId);
    if (this.players.size === 0) this.emptyListeners.forEach((fn) => fn(true));
  }
}
