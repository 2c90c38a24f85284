// One room: a Simulation stepped by its own TickClock, its players and their input buffers, the exact per-tick input
// record (stepped, recorded), and delivery of each tick's events and world frames to its members, with the snapshot
// fan-out (snapshot-fan-out.ts) that does the members' shared encoding work once per tick.
import { BodyFlag, type Vec3Like } from '../shared/physics/index.ts';
import type { BodyDescriptor, SimEvent, TickInputRecord } from '../shared/sim/types.ts';
import { ErrorCode } from '../shared/protocol/opcodes.ts';
import { GameMessageQueue } from './game-message-queue.ts';
import { NetMode } from '../shared/protocol/predict-messages.ts';
import type { InputCommand } from '../shared/sim/input.ts';
import { TICK_RATE_HZ } from '../shared/tick-rate.ts';
import type { HostedRoom, MemberSink, OfferTally, RoomEntry, Seat } from './hosted-room.ts';
import { OfferResult } from './input-buffer.ts';
import type { NetModeRequest } from './net-mode-policy.ts';
import { PredictFeed } from './predict-feed.ts';
import { enterRoom } from './local-seat.ts';
import { captureFrame } from './room-frame.ts';
import { RoomPlayers, type ConnectedPlayer } from './room-players.ts';
import { heldInput, RoomError, type JoinResult, type RoomInfo, type RoomOptions } from './room-options.ts';
import { RoomPace } from './room-pace.ts';
import { SnapshotFanOut } from './snapshot-fan-out.ts';
import { TickClock } from './tick-clock.ts';
import { TickTimes } from './monitor/tick-times.ts';

import type { RoomMember, RoomSimulation, WorldFrame } from './room-contracts.ts';
import type { RoomCarry } from './room-carry.ts';

export type { BodyStates, RoomMember, RoomRecorder, RoomSimulation, WorldFrame } from './room-contracts.ts';
export { heldInput, RoomError, type JoinResult, type RoomInfo, type RoomOptions } from './room-options.ts';

/** Whether a member takes predict-mode records now (a member without takesRecords does whenever it has deliverRecord). */
const takesRecords = (p: ConnectedPlayer): boolean => p.member.deliverRecord !== undefined && (p.member.takesRecords?.() ?? true);

/** A running room; build it with `new Room(sim, opts)` and call start(). */
export class Room implements HostedRoom {
  readonly id: string;
  readonly scenarioName: string;
  readonly description: string;
  readonly bounds: { min: Vec3Like; max: Vec3Like };
  readonly params: Readonly<Record<string, number>>;
  readonly seed: number | string;
  readonly sim: RoomSimulation;
  readonly tickClock: TickClock;
  /** The members' shared snapshot and event work (format, quantized frame, framed messages). */
  readonly snapshots: SnapshotFanOut;
  /** Recent tick wall times and the tick count, for the monitor. */
  readonly tickTimes = new TickTimes();
  /** How the room serves its members. */
  readonly netMode: NetMode;
  /** The mode the room was asked for ('auto' lets the cost estimate choose). */
  readonly netModeRequested: NetModeRequest;
  /** Predict mode's record stream and checkpoints (null in snapshot mode). */
  readonly predictFeed: PredictFeed | null;
  private readonly opts: RoomOptions;
  private readonly players: RoomPlayers;
  private readonly gameMessages = new GameMessageQueue();
  private closedReason: string | null = null;
  private snapshotAccumulator = 0;
  private cpuSecondsTotal = 0;
  private readonly paceMeter: RoomPace;
  /** Where in the tick period the room ticks on its thread (null: from when it starts). */
  private readonly phaseMs: number | null;
  private lastBodyCount = 0;
  // Static bodies the scene was built with: drawn from the welcome, never in snapshots. Statics spawned later
  // (streamed terrain) travel in snapshots instead, so clients already in the room learn about them.
  private readonly sceneStatics = new Set<number>();
  private readonly tickListeners = new Set<(record: TickInputRecord, events: readonly SimEvent[]) => void>();
  private readonly emptyListeners = new Set<(empty: boolean) => void>();
  private readonly closeListeners = new Set<(reason: string) => void>();

  constructor(sim: RoomSimulation, opts: RoomOptions) {
    if (!(opts.snapshotRateHz > 0 && opts.snapshotRateHz <= TICK_RATE_HZ)) {
      throw new Error(`room ${opts.id}: snapshot rate must be in (0, ${TICK_RATE_HZ}] Hz, got ${opts.snapshotRateHz}`);
    }
    this.sim = sim;
    this.opts = opts;
    this.players = new RoomPlayers(opts.maxInputLeadTicks ?? 120);
    this.id = opts.id;
    this.scenarioName = opts.scenarioName;
    this.description = opts.description ?? '';
    this.bounds = opts.bounds ?? { min: { x: -500, y: -500, z: -500 }, max: { x: 500, y: 500, z: 500 } };
    this.params = opts.params;
    this.seed = opts.seed;
    this.paceMeter = new RoomPace(opts.clock);
    this.netMode = opts.netMode ?? NetMode.Snapshot;
    this.netModeRequested = opts.netModeRequested ?? this.netMode;
    this.predictFeed = null;
    if (this.netMode === NetMode.Predict) {
      const save = sim.saveCheckpointBytes?.bind(sim);
      if (!save) throw new Error(`room ${opts.id}: predict mode needs a simulation with saveCheckpointBytes()`);
      const layout = { fields: sim.gameInputFields ?? [], kinds: sim.gameMessageKinds ?? [] };
      this.predictFeed = new PredictFeed({ get tick() { return sim.tick; }, stateHash: () => sim.stateHash(), saveCheckpointBytes: save }, opts.seed, opts.predictInputs, layout);
    }
    this.snapshots = new SnapshotFanOut({
      bounds: this.bounds,
      isSceneStatic: (id) => this.isSceneStatic(id),
      describe: (id) => sim.bodyDescriptor(id) ?? undefined,
      gameStateVersion: () => ((sim.gameStateFields?.length ?? 0) > 0 ? (sim.gameStateVersion ?? 0) : null),
      gameStateValues: () => sim.gameStateValues?.() ?? [],
    });
    const initial = sim.readBodyStates();
    this.lastBodyCount = initial.count;
    for (let i = 0; i < initial.count; i++) if ((initial.flags[i] & BodyFlag.Static) !== 0) this.sceneStatics.add(initial.ids[i]);
    if (opts.carried) this.adoptCarry(opts.carried);
    this.phaseMs = opts.phases?.take() ?? null;
    this.tickClock = new TickClock({
      clock: opts.clock,
      tickRateHz: TICK_RATE_HZ,
      maxCatchUpTicks: opts.maxCatchUpTicks ?? 4,
      catchUp: opts.catchUp,
      phaseMs: this.phaseMs,
      onTick: () => this.tickOnce(),
      onSlowdown: (r) => {
        opts.metrics.ticksSkipped.inc(r.skippedTicks);
        // Once per episode: a room that cannot keep up gives up ticks on nearly every wake-up.
        if (!this.paceMeter.rate().slow) opts.logger.warn({ room: this.id, tick: r.tick, skippedTicks: r.skippedTicks, lostMs: Math.round(r.lostMs) }, 'room cannot keep up: slowing down');
        this.paceMeter.slowedDown();
      },
      onError: (error) => this.fail(error),
    });
  }

  /** Snapshots per second sent to each member. */
  get snapshotRateHz(): number {
    return this.opts.snapshotRateHz;
  }

  /** Ticks on which a player's input had not arrived and the previous one was repeated (0 for unknown players). */
  missedInputTicks(playerId: number): number {
    return this.players.get(playerId)?.inputs.stats.repeated ?? 0;
  }

  /** Players in the room, counting those held for a reconnect (they keep their character and their place). */
  get clientCount(): number {
    return this.players.size;
  }

  /** Players whose link is down and whose character the room holds for a reconnect. */
  get heldCount(): number {
    return this.players.heldCount;
  }

  /** Ids of the players in the room (connected or held). */
  playerIds(): number[] {
    return this.players.ids();
  }

  /** Whether a player is in the room (connected or held). */
  hasPlayer(playerId: number): boolean {
    return this.players.has(playerId);
  }

  /** Ticks per second over the last second and whether the room runs slowed (cheap: no percentiles). */
  pace(): { ticksPerSecond: number; slow: boolean } {
    return this.paceMeter.rate();
  }

  /** CPU seconds of its thread this room's ticks have used since it opened (its load on its thread). */
  get cpuSeconds(): number {
    return this.cpuSecondsTotal;
  }

  /** Whether the room has closed. */
  get closed(): boolean {
    return this.closedReason !== null;
  }

  /** Starts ticking (unless empty and pausing when empty). */
  start(): void {
    if (this.closed) return;
    if (this.players.size > 0 || this.players.hasPendingLeaves || !(this.opts.pauseWhenEmpty ?? true)) this.tickClock.start();
  }

  /**
   * Stops the room between two ticks and lets this thread go of it for another to go on with (room-carry.ts): held
   * sends go out and the log is handed over first, then the room is gone from here without a close notice to anyone.
   */
  async handOff(): Promise<RoomCarry> {
    const sim = this.sim;
    if (!sim.saveCheckpointBytes) throw new RoomError(ErrorCode.Internal, `room ${this.id}: its simulation cannot checkpoint, so it cannot move`);
    if (this.closed) throw new RoomError(ErrorCode.RoomNotFound, `room ${this.id} is closed`);
    this.tickClock.stop();
    const log = (await this.opts.recorder?.handOff?.()) ?? null;
    if (this.closed) throw new RoomError(ErrorCode.RoomNotFound, `room ${this.id} closed while moving`);
    const carry: RoomCarry = {
      id: this.id, scenario: this.scenarioName, params: this.params, seed: this.seed, netModeRequested: this.netModeRequested,
      tick: sim.tick, checkpoint: sim.saveCheckpointBytes(), hash: sim.stateHash(), log, predictInputs: this.predictFeed?.inputs() ?? null,
      ...this.players.carry(), messages: this.gameMessages.waiting(),
      snapshotAccumulator: this.snapshotAccumulator, sceneStatics: [...this.sceneStatics], lastBodyCount: this.lastBodyCount, cpuSeconds: this.cpuSecondsTotal,
    };
    this.closedReason = 'moved to another thread';
    if (this.phaseMs !== null) this.opts.phases?.release(this.phaseMs);
    this.opts.metrics.players.dec(this.players.clear().length);
    sim.destroy();
    this.clearListeners();
    return carry;
  }

  private adoptCarry(c: RoomCarry): void {
    this.sceneStatics.clear();
    for (const id of c.sceneStatics) this.sceneStatics.add(id);
    this.lastBodyCount = c.lastBodyCount;
    this.snapshotAccumulator = c.snapshotAccumulator;
    this.cpuSecondsTotal = c.cpuSeconds;
    this.players.adopt(c);
    this.gameMessages.restore(c.messages);
    this.opts.metrics.players.inc(c.players.length);
  }

  /** The room's WASM heap (used and free bytes), or null when closed or the simulation does not say. */
  heapUsage(): { usedBytes: number; freeBytes: number } | null {
    const world = this.closed ? undefined : this.sim.world;
    if (!world) return null;
    const freeBytes = world.freeHeapBytes();
    return { usedBytes: world.totalHeapBytes() - freeBytes, freeBytes };
  }

  /** The room's summary. */
  info(): RoomInfo {
    const info: RoomInfo = { id: this.id, scenario: this.scenarioName, clients: this.players.size, tick: this.sim.tick, bodies: this.lastBodyCount, params: this.params, netMode: this.netMode, ...this.paceMeter.report() };
    if (this.opts.netModeNote) info.netModeNote = this.opts.netModeNote;
    return info;
  }

  /** Adds a member as a new player; its join goes into the next tick's record. Throws RoomError when refused. */
  join(member: RoomMember, name: string): JoinResult {
    if (this.closed) throw new RoomError(ErrorCode.RoomNotFound, `room ${this.id} is closed`);
    if (this.players.size >= this.opts.maxClients) {
      throw new RoomError(ErrorCode.RoomFull, `room ${this.id} is full (${this.opts.maxClients} clients)`);
    }
    const cap = this.opts.maxPlayers;
    if (cap !== undefined && this.players.size >= cap) {
      throw new RoomError(ErrorCode.RoomFull, `room ${this.id} is full: scenario ${this.scenarioName} serves at most ${cap} players at 60 Hz (its per-tick character budget, players.maxPlayers)`);
    }
    if (this.lastBodyCount + this.players.pendingJoinCount + 1 > this.opts.maxBodies) {
      throw new RoomError(ErrorCode.RoomFull, `room ${this.id} is at its body limit (${this.opts.maxBodies} bodies): no room for another character`);
    }
    const joinTick = this.sim.tick;
    const firstInputTick = joinTick + 1;
    const playerId = this.players.add(name, member, firstInputTick);
    this.opts.metrics.players.inc();
    if (this.players.size === 1) {
      this.emptyListeners.forEach((fn) => fn(false));
      this.tickClock.start();
    }
    return { playerId, joinTick, firstInputTick };
  }

  /**
   * A resumed room's players (in its world, their links gone with the crashed process) held like dropped players
   * until they reconnect or leave; new players get ids after `lastPlayerId`. Only before the first tick.
   */
  restorePlayers(players: ReadonlyArray<{ playerId: number; name: string; last: InputCommand }>, lastPlayerId: number): void {
    for (const { playerId, name, last } of players) {
      this.players.restore(playerId, name, heldInput(last), this.sim.tick, lastPlayerId);
      this.opts.metrics.players.inc();
    }
  }

  /** Seats a member (a new player, or a held one taken back) with its welcome; rejects with a RoomError when refused. */
  enter(sink: MemberSink, entry: RoomEntry): Promise<Seat> {
    try {
      return Promise.resolve(enterRoom(this, sink, entry, this.opts.metrics));
    } catch (error) {
      return Promise.reject(error instanceof Error ? error : new Error(String(error)));
    }
  }

  /** Removes a player; the leave goes into the next tick's record (a join not yet applied is simply dropped). */
  leave(playerId: number): void {
    if (!this.players.remove(playerId)) return;
    this.opts.metrics.players.dec();
    if (this.players.size === 0) this.emptyListeners.forEach((fn) => fn(true));
  }

  /**
   * The player's link dropped: its character stays in the world applying heldInput() every tick (recorded like any
   * command) and nothing is delivered to it, until reattach() or leave(). False when there is no such connected player.
   */
  detach(playerId: number): boolean {
    const p = this.players.get(playerId);
    if (!p || p.member === null || this.closed) return false;
    p.member = null;
    p.inputs.suspend(heldInput(p.inputs.lastApplied));
    return true;
  }

  /**
   * Hands a player (held, or still connected on a link being replaced) to a new member: same player id, same character,
   * no join or leave in the record. Null when the player is no longer in the room.
   */
  reattach(playerId: number, member: RoomMember): JoinResult | null {
    const p = this.players.get(playerId);
    if (!p || this.closed) return null;
    p.member = member;
    p.inputs.resume();
    return { playerId, joinTick: this.sim.tick, firstInputTick: p.inputs.nextTickToApply };
  }

  /** Offers a validated command a player stamped for `tick`. Unknown players are ignored (their leave raced it). */
  offerInput(playerId: number, tick: number, command: InputCommand): OfferResult | null {
    const p = this.players.get(playerId);
    if (!p) return null;
    const result = p.inputs.offer(tick, command);
    const m = this.opts.metrics;
    if (result === OfferResult.Accepted) m.inputsAccepted.inc();
    else if (result === OfferResult.Late) m.inputsLate.inc();
    else if (result === OfferResult.TooFar) m.inputsDropped.inc({ reason: 'too_far' });
    return result;
  }

  /** offerInput for a message's commands (ticks firstTick, firstTick + 1, …): the player looked up once. */
  offerInputs(playerId: number, firstTick: number, commands: readonly InputCommand[], tally: OfferTally): void {
    const p = this.players.get(playerId);
    if (!p) return;
    const m = this.opts.metrics;
    for (let i = 0; i < commands.length; i++) {
      const result = p.inputs.offer(firstTick + i, commands[i]);
      if (result === OfferResult.Accepted) m.inputsAccepted.inc();
      else if (result === OfferResult.Late) {
        m.inputsLate.inc();
        tally.inputsLate++;
      } else if (result === OfferResult.TooFar) {
        m.inputsDropped.inc({ reason: 'too_far' });
        tally.inputsTooFar++;
      }
    }
  }

  /**
   * Queues a player's game message for `tick` (a predicting client's own tick for it), or the next tick when that has
   * passed or none is given; no later than the input lead limit. Returns why it was refused, or null.
   */
  offerMessage(playerId: number, name: string, payload: readonly number[], tick?: number): string | null {
    if (!this.players.has(playerId)) return 'not in the room';
    const next = this.sim.tick;
    const at = tick === undefined || tick < next ? next : Math.min(tick, next + (this.opts.maxInputLeadTicks ?? 120));
    return this.gameMessages.offer(playerId, name, payload, this.sim.gameMessageKinds ?? [], at);
  }

  /** Whether a body is part of the scene's built static geometry (sent in the welcome, not in snapshots). */
  isSceneStatic(bodyId: number): boolean {
    return this.sceneStatics.has(bodyId);
  }

  /** Descriptors of the scene's built static geometry still present (a welcome's staticBodies). */
  staticDescriptors(): BodyDescriptor[] {
    return this.sim.staticDescriptors().filter((d) => this.sceneStatics.has(d.id));
  }

  /** Calls `fn` after every tick with the exact record stepped and the tick's events. Returns an unsubscribe. */
  onTick(fn: (record: TickInputRecord, events: readonly SimEvent[]) => void): () => void {
    this.tickListeners.add(fn);
    return () => this.tickListeners.delete(fn);
  }

  /** Calls `fn(true)` when the last member leaves and `fn(false)` when the first arrives. */
  onEmptyChange(fn: (empty: boolean) => void): () => void {
    this.emptyListeners.add(fn);
    return () => this.emptyListeners.delete(fn);
  }

  /** Calls `fn` once when the room closes. */
  onClose(fn: (reason: string) => void): () => void {
    this.closeListeners.add(fn);
    return () => this.closeListeners.delete(fn);
  }

  /** Builds this tick's record from pending leaves/joins and the players' buffers, steps, and delivers the results. */
  tickOnce(): void {
    if (this.closed) return;
    const started = performance.now();
    const cpuStarted = process.threadCpuUsage();
    const tick = this.sim.tick;
    const m = this.opts.metrics;
    const { leaves, joins, commands } = this.players.takeRecord(tick, () => m.inputsRepeated.inc());
    const messages = this.gameMessages.take(tick, (id) => this.players.has(id));
    const record: TickInputRecord = messages.length > 0 ? { tick, leaves, joins, commands, messages } : { tick, leaves, joins, commands };
    this.opts.recorder?.append(record);
    const stepStarted = performance.now();
    const events = this.sim.step(record);
    m.physicsStep.observe((performance.now() - stepStarted) / 1000);
    this.opts.recorder?.afterStep(this.sim.tick, () => this.sim.stateHash());
    this.players.joined(joins);
    m.ticks.inc();
    if (this.players.size === 0 && (this.opts.pauseWhenEmpty ?? true) && !this.players.hasPendingLeaves) {
      this.tickClock.stop();
      this.paceMeter.paused();
    }
    const send = this.deliver(tick, events, this.recordMessage(record));
    if (this.opts.recorder?.release) this.opts.recorder.release(tick, send);
    else send();
    for (const fn of this.tickListeners) fn(record, events);
    const seconds = (performance.now() - started) / 1000;
    const cpu = process.threadCpuUsage(cpuStarted);
    const cpuSeconds = (cpu.user + cpu.system) / 1e6;
    this.cpuSecondsTotal += cpuSeconds;
    this.paceMeter.ticked(seconds * 1000, cpuSeconds * 1000);
    m.tickDuration.observe(seconds);
    this.tickTimes.record(seconds * 1000);
    if (seconds > 1 / TICK_RATE_HZ) m.tickOverruns.inc();
  }

  /** Predict mode: the framed record of the tick just stepped, or null (and the coder stepped past it) when no member takes records. */
  private recordMessage(record: TickInputRecord): Uint8Array | null {
    const feed = this.predictFeed;
    if (feed === null) return null;
    if (this.players.someConnected(takesRecords)) return feed.frame(record);
    feed.skip(record);
    return null;
  }

  /** Does the tick's bookkeeping now and returns what sends its events and frame (possibly later, see release). */
  private deliver(tick: number, events: readonly SimEvent[], recordMessage: Uint8Array | null): () => void {
    // A removed scene static stays one until this tick is sent: a held frame taken before it still shows the body.
    const removed: number[] = [];
    for (const e of events) if (e.type === 'bodyRemoved') removed.push(e.bodyId);
    let frame: WorldFrame | null = null;
    this.snapshotAccumulator += this.opts.snapshotRateHz;
    if (this.snapshotAccumulator + 1e-9 >= TICK_RATE_HZ) {
      this.snapshotAccumulator -= TICK_RATE_HZ;
      const bodies = this.sim.readBodyStates();
      this.lastBodyCount = bodies.count;
      if (this.heldCount < this.players.size) frame = captureFrame(tick, bodies, this.sim, this.opts.recorder?.release ? (id) => this.isSceneStatic(id) : null, this.snapshots.takeSpareBodies());
    }
    return () => {
      if (this.closed) return;
      const members = this.players.connected();
      if (recordMessage !== null) for (const p of members) this.safely(p, () => p.member.deliverRecord?.(tick, recordMessage));
      if (events.length > 0) for (const p of members) this.safely(p, () => p.member.deliverEvents(tick, events));
      if (frame) for (const p of members) this.safely(p, () => p.member.deliverFrame(frame));
      for (const id of removed) this.sceneStatics.delete(id); // its id may be reused
    };
  }

  // A member that throws while taking a delivery is removed; the room and the other members carry on.
  private safely(p: ConnectedPlayer, fn: () => void): void {
    try {
      fn();
    } catch (error) {
      this.opts.logger.error({ room: this.id, playerId: p.playerId, err: error }, 'delivery to a member failed; removing it');
      this.leave(p.playerId);
      try {
        p.member.removed(`internal error delivering to you: ${error instanceof Error ? error.message : String(error)}`);
      } catch {
        // already gone; the room must not care
      }
    }
  }

  private fail(error: unknown): void {
    const message = error instanceof Error ? error.message : String(error);
    this.opts.logger.error({ room: this.id, tick: this.sim.tick, err: error }, 'room tick failed; closing the room');
    void this.close(`room error: ${message}`);
  }

  /** Stops ticking, tells every member why, closes the recorder and frees the simulation. Idempotent. */
  async close(reason: string): Promise<void> {
    if (this.closedReason !== null) return;
    this.closedReason = reason;
    this.tickClock.stop();
    if (this.phaseMs !== null) this.opts.phases?.release(this.phaseMs);
    const members = this.players.clear();
    this.opts.metrics.players.dec(members.length);
    for (const p of members) {
      try {
        p.member?.roomClosed(reason);
      } catch (error) {
        this.opts.logger.warn({ room: this.id, err: error }, 'member failed to take the close notice');
      }
    }
    try {
      if (this.opts.recorder) {
        let hash: string | null = null;
        try {
          hash = this.sim.stateHash();
        } catch {
          hash = null; // a failed simulation may not hash; the log ends unterminated
        }
        await this.opts.recorder.close(this.sim.tick, hash);
      }
    } catch (error) {
      this.opts.logger.error({ room: this.id, err: error }, 'closing the room recording failed');
    }
    const tick = this.sim.tick;
    this.sim.destroy();
    this.opts.logger.info({ room: this.id, reason, tick }, 'room closed');
    for (const fn of this.closeListeners) fn(reason);
    this.clearListeners();
  }

  // Nothing outlives the room through its listeners (they close over sessions, managers, recorders).
  private clearListeners(): void {
    this.tickListeners.clear();
    this.emptyListeners.clear();
    this.closeListeners.clear();
  }
}
