// The typed network client for browsers and Node 24: connect(url, {name, room}) joins a room, keeps the clock in
// sync, sends inputs ahead of the server tick, decodes and acks snapshots into an interpolation buffer, reports
// events and errors, and reconnects with backoff after drops, asking for the same player back with the resume token
// of the last welcome; a `room-moved` bye (a fleet of servers) sends it to the server that hosts the room. One
// LinkSession per connection does the wire work.
import type { Clock, TimerHandle } from '../shared/clock.ts';
import { ByeReason } from '../shared/protocol/opcodes.ts';
import { TOKEN_PATTERN } from '../shared/protocol/limits.ts';
import { checkPlayerName, checkRoomId } from '../shared/protocol/validation.ts';
import type { ErrorMessage, ServerByeMessage, WelcomeMessage } from '../shared/protocol/server-messages.ts';
import { NEUTRAL_INPUT, type InputCommand } from '../shared/sim/input.ts';
import { gameMessagePayload } from '../shared/sim/game-messages.ts';
import type { GameStateValue, GameStateValues } from '../shared/sim/game-state.ts';
import type { BodyDescriptor, SimEvent } from '../shared/sim/types.ts';
import { RealClock } from './clock.ts';
import { Emitter } from './emitter.ts';
import { GameInputMapper, type PlayerInput } from './game-input.ts';
import { GameStateMirror, type GameStateChange } from './game-state.ts';
import type { InputLeadOptions } from './input-sender.ts';
import type { InterpolatedFrame, InterpolationOptions } from './interpolation.ts';
import { LinkSession, type LinkClosedInfo, type SnapshotInfo } from './link-session.ts';
import { checkInputDelay, type PredictedFrame, type PredictionStats, type PredictOptions } from './prediction/predict-session.ts';
import { backoffDelayMs, isRetryable, reconnectPolicy, type ReconnectOptions, type ReconnectPolicy } from './reconnect-policy.ts';
import type { TransportFactory } from './transport.ts';
import { webSocketTransport } from './websocket-transport.ts';

/** Options of connect(). */
export interface NetClientOptions {
  /** Display name (1–32 characters). */
  name: string;
  /** Room to join; null or absent: the server's default room (or the seat token's room). */
  room?: string | null;
  /** Seat token for the first join (a game backend gets it from `POST /api/rooms/:id/seats`); used once. */
  seat?: string;
  /** Resume token of an earlier connection (see `resumeToken`): the first hello asks for that player back. */
  resumeToken?: string;
  /** Whether reconnects ask for the same player back with the last welcome's resume token. Default true. */
  resume?: boolean;
  /** How to open links. Default: the global WebSocket. */
  transport?: TransportFactory;
  /** Time source. Default: performance.now() and setTimeout. */
  clock?: Clock;
  /** Commands per input message (newest + repeats), 1–16. Default 4. */
  inputRedundancy?: number;
  /** Ping period after the first few (ms). Default 1000. */
  pingIntervalMs?: number;
  /** Pings sent 100 ms apart right after the welcome. Default 5. */
  initialPings?: number;
  /** Reconnect settings, or false for none. */
  reconnect?: ReconnectOptions | false;
  /** Random source in [0, 1) for backoff jitter. Default Math.random. */
  random?: () => number;
  /** Interpolation tuning (delay intervals, extrapolation limit, …). */
  interpolation?: Partial<Omit<InterpolationOptions, 'tickRateHz' | 'snapshotRateHz'>>;
  /** Input lead tuning. */
  lead?: Partial<Omit<InputLeadOptions, 'tickRateHz'>>;
  /** Predicted play: in rooms whose welcome says `netMode: 'predict'` the client runs the simulation itself. */
  predict?: PredictOptions;
}

/** Lifecycle of a client: connecting → connected → (reconnecting → connecting → connected)* → closed. */
export type NetClientState = 'connecting' | 'connected' | 'reconnecting' | 'closed';

/** Why a client stopped for good. */
export interface ClosedInfo {
  /** 'client-closed', a server bye reason, a server error code, 'unreachable' or 'disconnected'. */
  reason: string;
  /** A sentence for people. */
  detail: string;
}

/** Events of NetClient and their payloads. */
export interface NetClientEvents {
  /** The state changed. */
  state: NetClientState;
  /** A (re)connection was welcomed; descriptors and interpolation start afresh. */
  welcome: WelcomeMessage;
  /** A snapshot was decoded (its ack rides on the next input message, or goes alone within a tick). */
  snapshot: SnapshotInfo;
  /** Simulation events, in tick order. */
  events: SimEvent[];
  /** The room's game state changed (with the snapshot that brought it): the whole state and the changed names. */
  gameState: GameStateChange;
  /** The server refused something (the connection may stay open). */
  serverError: ErrorMessage;
  /** The server said goodbye. */
  bye: ServerByeMessage;
  /** A server message could not be used (undecodable, snapshot without baseline, …). */
  protocolError: string;
  /** The room is hosted by another server: the client connects to `url` now (WebSocket URL). */
  moved: { url: string; message: string };
  /**
   * The link dropped and another attempt is scheduled. `serverRestarting`: an attempt found nothing listening after
   * the link had worked, so the server process itself went away (a crash and restart: `serve --resume` keeps players).
   */
  reconnecting: { attempt: number; delayMs: number; reason: string; serverRestarting: boolean };
  /** The client stopped for good. */
  closed: ClosedInfo;
}

/** Live numbers for a HUD. */
export interface NetClientStats {
  state: NetClientState;
  playerId: number | null;
  roomId: string | null;
  /** Estimated server tick now (fractional), null before a welcome. */
  serverTick: number | null;
  rttMs: number | null;
  jitterMs: number;
  /** Server clock minus local clock (ms). */
  clockOffsetMs: number | null;
  leadTicks: number | null;
  /** The newest tick an input was sent for. */
  newestInputTick: number;
  /** Ticks the server repeated our previous input because the new one was late (from the last pong). */
  missedInputTicks: number | null;
  /** The room's ticks per second over the last second and whether it runs slowed (from the last pong). */
  roomPace: { ticksPerSecond: number; slow: boolean } | null;
  kbpsIn: number;
  bytesIn: number;
  bytesOut: number;
  snapshots: number;
  snapshotsFailed: number;
  lastSnapshotTick: number | null;
  reconnects: number;
  /** Predicted play's numbers; null when this link does not predict (snapshot room, or no predict option). */
  prediction: PredictionStats | null;
}

/** Room moves followed in a row (without a welcome between them) before the client gives up. */
const MAX_ROOM_MOVES = 3;

/** Whether a room-moved bye's URL is one the client may follow: ws://, wss://, or the scheme it is connected with. */
function isMoveTarget(url: string | undefined, current: string): url is string {
  if (url === undefined) return false;
  try {
    const protocol = new URL(url).protocol;
    return protocol === 'ws:' || protocol === 'wss:' || protocol === new URL(current).protocol;
  } catch {
    return false;
  }
}

/** Descriptors are kept this long (ticks) after their body left the snapshots, for frames still being drawn. */
const DESCRIPTOR_GRACE_TICKS = 180;

/** Calls fn for each id of ascending `before` missing from ascending `after`. */
function forEachMissing(before: Uint32Array, after: Uint32Array, fn: (id: number) => void): void {
  let j = 0;
  for (let i = 0; i < before.length; i++) {
    while (j < after.length && after[j] < before[i]) j++;
    if (j >= after.length || after[j] !== before[i]) fn(before[i]);
  }
}

/** Binary search in an ascending id list. */
function sortedHas(ids: Uint32Array, id: number): boolean {
  let lo = 0;
  let hi = ids.length - 1;
  while (lo <= hi) {
    const mid = (lo + hi) >> 1;
    if (ids[mid] === id) return true;
    if (ids[mid] < id) lo = mid + 1;
    else hi = mid - 1;
  }
  return false;
}

/** A client of one room. Create it with connect(). */
export class NetClient {
  private urlValue: string;
  private moves = 0;
  private readonly name: string;
  private readonly requestedRoom: string | null;
  private readonly clock: Clock;
  private readonly transport: TransportFactory;
  private readonly policy: ReconnectPolicy;
  private readonly random: () => number;
  private readonly opts: NetClientOptions;
  private readonly emitter = new Emitter<NetClientEvents>();
  private session: LinkSession | null = null;
  private stateValue: NetClientState = 'connecting';
  private input: InputCommand = { ...NEUTRAL_INPUT };
  private readonly gameInput = new GameInputMapper();
  private readonly gameStateMirror = new GameStateMirror();
  private welcomeMsg: WelcomeMessage | null = null;
  private readonly dynamic = new Map<number, BodyDescriptor>();
  private pendingDescriptorRemoval: Array<{ id: number; afterTick: number }> = [];
  private previousIds: Uint32Array | null = null;
  private attempts = 0;
  private reconnectCount = 0;
  private retryTimer: TimerHandle | null = null;
  /** Since the last welcome: the server went away (nothing listening on a retry). */
  private serverRestarting = false;
  private closedInfo: ClosedInfo | null = null;
  private resumeTokenValue: string | null;
  private waiters: Array<{ resolve: (w: WelcomeMessage) => void; reject: (e: Error) => void }> = [];

  constructor(url: string, opts: NetClientOptions) {
    const name = checkPlayerName(opts.name);
    if (!name.ok) throw new Error(`connect: ${name.error}`);
    const room = checkRoomId(opts.room ?? null);
    if (!room.ok) throw new Error(`connect: ${room.error}`);
    if (typeof url !== 'string' || url === '') throw new Error('connect: url must be a non-empty string');
    for (const key of ['seat', 'resumeToken'] as const) {
      const token = opts[key];
      if (token !== undefined && (typeof token !== 'string' || !TOKEN_PATTERN.test(token))) throw new Error(`connect: ${key} must be a token of A-Z a-z 0-9 _ . - characters`);
    }
    if (opts.predict?.inputDelayTicks !== undefined) checkInputDelay(opts.predict.inputDelayTicks);
    this.resumeTokenValue = opts.resumeToken ?? null;
    this.urlValue = url;
    this.name = name.name;
    this.requestedRoom = room.room;
    this.opts = opts;
    this.clock = opts.clock ?? new RealClock();
    this.transport = opts.transport ?? webSocketTransport;
    this.policy = reconnectPolicy(opts.reconnect);
    this.random = opts.random ?? Math.random;
    this.open();
  }

  /** The server URL the client connects to now (the one given to connect(), or where a room-moved bye sent it). */
  get url(): string {
    return this.urlValue;
  }

  /** Current lifecycle state. */
  get state(): NetClientState {
    return this.stateValue;
  }

  /** The latest welcome (null before the first). */
  get welcome(): WelcomeMessage | null {
    return this.welcomeMsg;
  }

  /** This client's player id in the current connection. */
  get playerId(): number | null {
    return this.welcomeMsg?.playerId ?? null;
  }

  /**
   * The token that takes this player back on a new connection within the server's grace window (the client uses it
   * by itself after a drop; keep it, e.g. in sessionStorage, to resume after a page reload). Null before a welcome.
   */
  get resumeToken(): string | null {
    return this.resumeTokenValue;
  }

  /** How the client ended, once closed. */
  get closed(): ClosedInfo | null {
    return this.closedInfo;
  }

  /**
   * The room's replicated game state by field name (empty until the first snapshot after a welcome); type it with
   * your scenario's state: `client.gameState<{ score: number; phase: string }>()`.
   */
  gameState<S extends GameStateValues = GameStateValues>(): Readonly<Partial<S>> {
    return this.gameStateMirror.state as Readonly<Partial<S>>;
  }

  /** Subscribes to an event; returns the unsubscribe function. */
  on<K extends keyof NetClientEvents>(type: K, listener: (payload: NetClientEvents[K]) => void): () => void {
    return this.emitter.on(type, listener);
  }

  /** Resolves with the next welcome (or the current one when connected); rejects if the client closes first. */
  whenConnected(): Promise<WelcomeMessage> {
    if (this.stateValue === 'connected' && this.welcomeMsg) return Promise.resolve(this.welcomeMsg);
    if (this.closedInfo) return Promise.reject(new Error(`client closed: ${this.closedInfo.reason}: ${this.closedInfo.detail}`));
    return new Promise((resolve, reject) => this.waiters.push({ resolve, reject }));
  }

  /**
   * Sets the command sent for the coming ticks (kept across reconnects), with the scenario's game input fields by
   * name (`{...cmd, kick: 1}`); throws on an invalid value or a field the scenario does not declare.
   */
  setInput(cmd: InputCommand | PlayerInput): void {
    this.input = this.gameInput.set(cmd);
    this.session?.setInput(this.input);
  }

  /**
   * Sends a game message the scenario declares (`sendMessage('pickTeam', { team: 1 })`); the server stamps it with its
   * next tick. Throws while not connected (messages are not queued across reconnects) and for an undeclared name,
   * payload field or out-of-range value.
   */
  sendMessage(name: string, payload: Readonly<Record<string, number>> = {}): void {
    const session = this.connectedSession();
    if (!session || !this.welcomeMsg || this.stateValue !== 'connected') throw new Error(`sendMessage(${name}): not connected`);
    session.sendGameMessage(name, gameMessagePayload(name, payload, this.welcomeMsg.scenario.game?.messages ?? []));
  }

  /** The estimated server tick (fractional) at a local time (default now); null before a welcome. */
  serverTick(nowMs: number = this.clock.nowMs()): number | null {
    const sync = this.connectedSession()?.clockSync;
    return sync ? sync.serverTickAt(nowMs) : null;
  }

  /** The interpolated world at a local time (default now); mode 'empty' before any snapshot. */
  sample(nowMs: number = this.clock.nowMs()): InterpolatedFrame {
    const frame = this.connectedSession()?.sample(nowMs);
    return frame ?? { view: null, renderTick: 0, mode: 'empty', bufferDepth: 0, delayMs: 0, targetDelayMs: 0, jitterMs: 0, extrapolatedTicks: 0 };
  }

  /** The descriptor of a body (dynamic or static; while predicting, from the local simulation first). */
  descriptor(id: number): BodyDescriptor | undefined {
    return this.connectedSession()?.prediction?.descriptor(id) ?? this.dynamic.get(id) ?? this.welcomeMsg?.staticBodies.find((d) => d.id === id);
  }

  /**
   * The predicted world (smoothed poses of every body and character) while this client predicts, else null: draw
   * sample() then. Call it once per drawn frame: it first runs the input loop's step for now, so the own player's
   * newest input is in the frame (its tick came due) whatever the timers' phase.
   */
  predicted(): PredictedFrame | null {
    return this.connectedSession()?.predictedFrame() ?? null;
  }

  /** Stops predicting on this connection and goes back to interpolated snapshots (stats().prediction says why). */
  stopPredicting(reason = 'stopped by the app'): void {
    this.connectedSession()?.prediction?.fallBack(reason);
  }

  /** Descriptors of the non-static bodies known now, by id. */
  dynamicDescriptors(): ReadonlyMap<number, BodyDescriptor> {
    return this.dynamic;
  }

  /** Live numbers for a HUD. */
  stats(nowMs: number = this.clock.nowMs()): NetClientStats {
    const s = this.connectedSession();
    const sync = s?.clockSync ?? null;
    return {
      state: this.stateValue,
      playerId: this.playerId,
      roomId: this.welcomeMsg?.roomId ?? null,
      serverTick: sync ? sync.serverTickAt(nowMs) : null,
      rttMs: sync?.rttMs ?? null,
      jitterMs: sync?.jitterMs ?? 0,
      clockOffsetMs: sync?.offsetMs ?? null,
      leadTicks: s?.leadTicks ?? null,
      newestInputTick: s?.newestInputTick ?? -1,
      missedInputTicks: s?.serverMissedInputTicks ?? null,
      roomPace: s?.serverRoomPace ?? null,
      kbpsIn: this.session?.kbpsIn(nowMs) ?? 0,
      bytesIn: this.session?.counters.bytesIn ?? 0,
      bytesOut: this.session?.counters.bytesOut ?? 0,
      snapshots: this.session?.counters.snapshots ?? 0,
      snapshotsFailed: this.session?.counters.snapshotsFailed ?? 0,
      lastSnapshotTick: s?.latestFrame?.tick ?? null,
      reconnects: this.reconnectCount,
      prediction: s?.prediction?.stats() ?? null,
    };
  }

  /** Leaves: says bye, closes the link, cancels reconnects. Idempotent. */
  close(): void {
    if (this.stateValue === 'closed') return;
    if (this.retryTimer) this.clock.clearTimer(this.retryTimer);
    this.retryTimer = null;
    const s = this.session;
    this.finish({ reason: 'client-closed', detail: 'closed by the client' });
    s?.close();
  }

  private connectedSession(): LinkSession | null {
    return this.session !== null && this.session.welcome !== null ? this.session : null;
  }

  private setState(state: NetClientState): void {
    if (this.stateValue === state) return;
    this.stateValue = state;
    this.emitter.emit('state', state);
  }

  private open(): void {
    this.setState('connecting');
    const room = this.welcomeMsg?.roomId ?? this.requestedRoom;
    const session: LinkSession = new LinkSession(
      {
        url: this.url,
        name: this.name,
        room,
        transport: this.transport,
        clock: this.clock,
        inputRedundancy: this.opts.inputRedundancy ?? 4,
        pingIntervalMs: this.opts.pingIntervalMs ?? 1000,
        initialPings: this.opts.initialPings ?? 5,
        interpolation: this.opts.interpolation ?? {},
        lead: this.opts.lead ?? {},
        input: this.input,
        // A seat is used once: only until the first welcome. Later links ask for the same player back instead.
        seatToken: this.welcomeMsg === null ? this.opts.seat : undefined,
        resumeToken: this.opts.resume !== false && this.resumeTokenValue !== null ? this.resumeTokenValue : undefined,
        predict: this.opts.predict,
      },
      {
        welcome: (w) => this.session === session && this.onWelcome(w),
        snapshot: (s) => this.session === session && this.onSnapshot(s),
        events: (e) => this.session === session && this.emitter.emit('events', e),
        gameState: (values) => this.session === session && this.onGameState(values),
        serverError: (e) => this.session === session && this.emitter.emit('serverError', e),
        bye: (b) => this.session === session && this.emitter.emit('bye', b),
        protocolError: (m) => this.session === session && this.emitter.emit('protocolError', m),
        closed: (info) => this.session === session && this.onLinkClosed(info),
      },
    );
    this.session = session;
  }

  private onWelcome(w: WelcomeMessage): void {
    const fitted = this.gameInput.welcome(w.scenario.game?.input ?? []);
    this.input = fitted.command;
    this.gameStateMirror.welcome(w.scenario.game?.state ?? []);
    this.session?.setInput(this.input);
    if (fitted.unknown.length > 0) this.emitter.emit('protocolError', `setInput: the scenario declares no game input ${fitted.unknown.join(', ')}; dropped`);
    this.welcomeMsg = w;
    this.serverRestarting = false;
    this.resumeTokenValue = w.resumeToken;
    this.attempts = 0;
    this.moves = 0;
    this.dynamic.clear();
    this.pendingDescriptorRemoval = [];
    for (const d of w.dynamicBodies) this.dynamic.set(d.id, d);
    this.previousIds = Uint32Array.from(w.dynamicBodies.map((d) => d.id)).sort();
    this.setState('connected');
    this.emitter.emit('welcome', w);
    for (const waiter of this.waiters.splice(0)) waiter.resolve(w);
  }

  private onGameState(values: GameStateValue[]): void {
    const change = this.gameStateMirror.apply(values);
    if (typeof change === 'string') this.emitter.emit('protocolError', change);
    else if (change !== null) this.emitter.emit('gameState', change);
  }

  private onSnapshot(s: SnapshotInfo): void {
    for (const d of s.descriptors) this.dynamic.set(d.id, d);
    const ids = s.frame.bodyIds;
    if (this.session?.latestFrame === s.frame) {
      // Bodies that left since the previous newest frame lose their descriptor after a grace period
      // (the interpolation buffer may still be drawing them).
      if (this.previousIds !== null) forEachMissing(this.previousIds, ids, (id) => this.pendingDescriptorRemoval.push({ id, afterTick: s.tick + DESCRIPTOR_GRACE_TICKS }));
      this.previousIds = ids;
      if (this.pendingDescriptorRemoval.length > 0 && this.pendingDescriptorRemoval[0].afterTick <= s.tick) {
        this.pendingDescriptorRemoval = this.pendingDescriptorRemoval.filter((p) => {
          if (p.afterTick > s.tick) return true;
          if (!sortedHas(ids, p.id)) this.dynamic.delete(p.id);
          return false;
        });
      }
    }
    this.emitter.emit('snapshot', s);
  }

  private onLinkClosed(info: LinkClosedInfo): void {
    this.session = null;
    if (this.stateValue === 'closed') return;
    const byeReason = info.bye?.reason ?? null;
    const errorCode = info.errorBeforeWelcome?.code ?? null;
    const why = info.bye ? `${info.bye.reason}: ${info.bye.message}` : info.errorBeforeWelcome ? `${info.errorBeforeWelcome.code}: ${info.errorBeforeWelcome.message}` : `closed (${info.code}${info.reason ? `: ${info.reason}` : ''})`;
    if (byeReason === ByeReason.RoomMoved) {
      this.followMove(info.bye?.url, why);
      return;
    }
    if (!isRetryable(byeReason, errorCode)) {
      this.finish({ reason: byeReason ?? errorCode ?? 'disconnected', detail: why });
      return;
    }
    if (!this.policy.enabled) {
      this.finish({ reason: byeReason ?? errorCode ?? 'disconnected', detail: why });
      return;
    }
    if (this.attempts >= this.policy.maxAttempts) {
      this.finish({ reason: 'unreachable', detail: `gave up after ${this.attempts} attempts; last: ${why}` });
      return;
    }
    this.attempts++;
    const delayMs = backoffDelayMs(this.policy, this.attempts, this.random);
    if (!info.opened && this.welcomeMsg !== null) this.serverRestarting = true;
    this.setState('reconnecting');
    this.emitter.emit('reconnecting', { attempt: this.attempts, delayMs, reason: why, serverRestarting: this.serverRestarting });
    this.retryTimer = this.clock.setTimer(delayMs, () => {
      this.retryTimer = null;
      if (this.stateValue !== 'reconnecting') return;
      this.reconnectCount++;
      this.open();
    });
  }

  /** Connects at once to the server a room-moved bye named (a bounded number of times in a row). */
  private followMove(url: string | undefined, why: string): void {
    if (!isMoveTarget(url, this.urlValue)) {
      this.finish({ reason: ByeReason.RoomMoved, detail: `${why} (no usable ws:// or wss:// URL to follow)` });
      return;
    }
    if (this.moves >= MAX_ROOM_MOVES) {
      this.finish({ reason: ByeReason.RoomMoved, detail: `moved ${this.moves} times in a row without a welcome; last: ${why}` });
      return;
    }
    this.moves++;
    this.urlValue = url;
    this.emitter.emit('moved', { url, message: why });
    this.open();
  }

  private finish(info: ClosedInfo): void {
    this.closedInfo = info;
    this.setState('closed');
    this.emitter.emit('closed', info);
    for (const waiter of this.waiters.splice(0)) waiter.reject(new Error(`client closed: ${info.reason}: ${info.detail}`));
  }
}

/** Starts connecting to a server URL (ws:// or wss://) and returns the client at once; await whenConnected(). */
export function connect(url: string, options: NetClientOptions): NetClient {
  return new NetClient(url, options);
}
