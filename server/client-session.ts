// One client connection from hello to bye: validates every incoming frame, enforces per-client rate and error limits,
// joins a room, feeds inputs/acks/pings to it, and sends welcome, events (reliable) and snapshots (skipped when the
// socket is backed up). Nothing a client sends reaches the room unvalidated or under another player's id.
import {
  ByeReason,
  createSnapshotFormat,
  decodeClientMessage,
  encodeServerMessage,
  ErrorCode,
  MAX_CLIENT_MESSAGE_BYTES,
  PROTOCOL_VERSION,
  quantizeFrame,
  SharedFrameWork,
  SnapshotEncoder,
  snapshotFormatSpec,
  type ClientMessage,
  type QuantizedFrame,
  type ServerMessage,
  type SnapshotFormat,
} from '../shared/protocol/index.ts';
import type { BodyDescriptor, SimEvent } from '../shared/sim/types.ts';
import type { Clock, TimerHandle } from './clock.ts';
import { CloseCode, type ServerConnection } from './connection.ts';
import { OfferResult } from './input-buffer.ts';
import type { Logger } from './logger.ts';
import type { ServerMetrics } from './metrics.ts';
import { RateLimiter, type RateLimit } from './rate-limiter.ts';
import { RoomError, type Room, type RoomMember, type WorldFrame } from './room.ts';
import type { RoomManager } from './room-manager.ts';

/** Each room's latest quantized frame and the body copies it came from (the next frame's starting point). */
const lastQuantized = new WeakMap<Room, { bodies: WorldFrame['bodies']; frame: QuantizedFrame }>();
/** Framed events messages by the room's event list of a tick (the list is never changed after delivery). */
const eventMessages = new WeakMap<readonly SimEvent[], Uint8Array>();

/** Per-client limits. */
export interface SessionLimits {
  /** All messages: sustained rate and burst. Beyond it the client is disconnected (flood). */
  messages: RateLimit;
  /** Input messages alone. */
  inputs: RateLimit;
  /** Refused messages: a few are answered with errors; past this bucket the client is disconnected. */
  badMessages: RateLimit;
  /** Largest accepted frame (bytes). */
  maxMessageBytes: number;
  /** Time allowed between connecting and a valid hello. */
  helloTimeoutMs: number;
  /** Skip snapshots while this many bytes are queued on the socket. */
  snapshotSkipBufferedBytes: number;
  /** Disconnect when this many bytes are queued (reliable messages cannot be dropped, nor queued without bound). */
  maxBufferedBytes: number;
}

/**
 * Defaults: room for 60 inputs + 60 acks + pings per second with slack, and a short leash on garbage. The bursts
 * hold ~10 s of a well-behaved client's traffic: after a network stall (or a server pause) its on-time messages
 * arrive all at once, and that must not read as a flood; the sustained rates still cap a flooder.
 */
export const DEFAULT_SESSION_LIMITS: Readonly<SessionLimits> = Object.freeze({
  messages: { perSecond: 300, burst: 1200 },
  inputs: { perSecond: 150, burst: 600 },
  badMessages: { perSecond: 0.5, burst: 10 },
  maxMessageBytes: MAX_CLIENT_MESSAGE_BYTES,
  helloTimeoutMs: 5_000,
  snapshotSkipBufferedBytes: 256 * 1024,
  maxBufferedBytes: 8 * 1024 * 1024,
});

/** What a session needs from the server. */
export interface SessionContext {
  clock: Clock;
  metrics: ServerMetrics;
  logger: Logger;
  rooms: RoomManager;
  limits: SessionLimits;
  /** Called once when the session ends. */
  onEnd(session: ClientSession): void;
}

/** Counters of one session (tests and logs). */
export interface SessionStats {
  messagesReceived: number;
  badMessages: number;
  errorsSent: number;
  snapshotsSent: number;
  snapshotsSkipped: number;
  snapshotBytes: number;
  bytesSent: number;
  inputsLate: number;
  inputsTooFar: number;
}

const formats = new WeakMap<Room, SnapshotFormat>();
function formatFor(room: Room): SnapshotFormat {
  let f = formats.get(room);
  if (!f) {
    f = createSnapshotFormat(room.bounds);
    formats.set(room, f);
  }
  return f;
}

let nextSessionId = 1;

/** One connected client. */
export class ClientSession implements RoomMember {
  readonly id = nextSessionId++;
  readonly conn: ServerConnection;
  readonly stats: SessionStats = { messagesReceived: 0, badMessages: 0, errorsSent: 0, snapshotsSent: 0, snapshotsSkipped: 0, snapshotBytes: 0, bytesSent: 0, inputsLate: 0, inputsTooFar: 0 };
  private readonly ctx: SessionContext;
  private readonly messageLimiter: RateLimiter;
  private readonly inputLimiter: RateLimiter;
  private readonly badLimiter: RateLimiter;
  private state: 'hello' | 'joining' | 'joined' | 'closed' = 'hello';
  private helloTimer: TimerHandle | null;
  private room: Room | null = null;
  private playerId = 0;
  private encoder: SnapshotEncoder | null = null;

  constructor(conn: ServerConnection, ctx: SessionContext) {
    this.conn = conn;
    this.ctx = ctx;
    this.messageLimiter = new RateLimiter(ctx.clock, ctx.limits.messages);
    this.inputLimiter = new RateLimiter(ctx.clock, ctx.limits.inputs);
    this.badLimiter = new RateLimiter(ctx.clock, ctx.limits.badMessages);
    this.helloTimer = ctx.clock.setTimer(ctx.limits.helloTimeoutMs, () => {
      this.helloTimer = null;
      if (this.state === 'hello') this.end(ByeReason.Timeout, `no hello within ${ctx.limits.helloTimeoutMs} ms`, CloseCode.PolicyViolation);
    });
    ctx.metrics.connections.inc();
    ctx.metrics.clients.inc();
    conn.attach({
      message: (data, binary) => this.onMessage(data, binary),
      close: (code, reason) => this.onClosed(code, reason),
    });
  }

  /** The player id once joined (0 before). */
  get player(): number {
    return this.playerId;
  }

  /** The room once joined. */
  get currentRoom(): Room | null {
    return this.room;
  }

  /** Whether the session has ended. */
  get ended(): boolean {
    return this.state === 'closed';
  }

  private onMessage(data: Uint8Array, binary: boolean): void {
    if (this.state === 'closed') return;
    const m = this.ctx.metrics;
    this.stats.messagesReceived++;
    m.messagesReceived.inc();
    m.bytesReceived.inc(data.length);
    if (!this.messageLimiter.take()) {
      this.end(ByeReason.Flood, `more than ${this.ctx.limits.messages.perSecond} messages per second`, CloseCode.PolicyViolation);
      return;
    }
    if (!binary) {
      this.refuse(ErrorCode.Malformed, 'text frames are not accepted: send binary msgpack');
      return;
    }
    const decoded = decodeClientMessage(data, this.ctx.limits.maxMessageBytes);
    if (!decoded.ok) {
      this.refuse(decoded.code, decoded.error);
      return;
    }
    if (decoded.clampedCommands > 0) m.inputsClamped.inc(decoded.clampedCommands);
    try {
      this.handle(decoded.message);
    } catch (error) {
      // A server-side bug while handling a valid message: drop this client, never the room.
      this.ctx.logger.error({ session: this.id, err: error }, 'handling a client message failed');
      this.end(ByeReason.Kicked, 'internal error handling your message', CloseCode.InternalError);
    }
  }

  private handle(msg: ClientMessage): void {
    switch (msg.type) {
      case 'hello':
        this.onHello(msg.version, msg.name, msg.room);
        return;
      case 'input': {
        if (this.state !== 'joined' || !this.room) {
          this.refuse(ErrorCode.UnexpectedMessage, 'input before the welcome');
          return;
        }
        if (!this.inputLimiter.take()) {
          this.end(ByeReason.Flood, `more than ${this.ctx.limits.inputs.perSecond} input messages per second`, CloseCode.PolicyViolation);
          return;
        }
        for (let i = 0; i < msg.commands.length; i++) {
          const r = this.room.offerInput(this.playerId, msg.firstTick + i, msg.commands[i]);
          if (r === OfferResult.Late) this.stats.inputsLate++;
          else if (r === OfferResult.TooFar) this.stats.inputsTooFar++;
        }
        return;
      }
      case 'ack':
        if (this.state !== 'joined' || !this.encoder) {
          this.refuse(ErrorCode.UnexpectedMessage, 'ack before the welcome');
          return;
        }
        this.encoder.acknowledge(msg.tick);
        return;
      case 'ping': {
        const room = this.room;
        this.send({
          type: 'pong',
          clientTimeMs: msg.clientTimeMs,
          serverTick: room ? room.sim.tick : 0,
          serverTimeMs: this.ctx.clock.nowMs(),
          missedInputTicks: room ? room.missedInputTicks(this.playerId) : 0,
        });
        return;
      }
      case 'bye':
        this.end(ByeReason.ClientBye, 'goodbye', CloseCode.Normal);
        return;
    }
  }

  private onHello(version: number, name: string, roomId: string | null): void {
    if (this.state !== 'hello') {
      this.refuse(ErrorCode.UnexpectedMessage, 'hello was already received');
      return;
    }
    if (version !== PROTOCOL_VERSION) {
      this.end(ByeReason.VersionMismatch, `server speaks protocol ${PROTOCOL_VERSION}, client sent ${version}`, CloseCode.PolicyViolation);
      return;
    }
    this.state = 'joining';
    if (this.helloTimer) this.ctx.clock.clearTimer(this.helloTimer);
    this.helloTimer = null;
    this.conn.helloed?.();
    this.ctx.rooms.resolve(roomId === null ? {} : { roomId }).then(
      (room) => this.joinRoom(room, name),
      (error: unknown) => this.joinFailed(error),
    );
  }

  private joinRoom(room: Room, name: string): void {
    if (this.state !== 'joining') return; // the client left while the room was being created
    let joined;
    try {
      joined = room.join(this, name);
    } catch (error) {
      this.joinFailed(error);
      return;
    }
    this.room = room;
    this.playerId = joined.playerId;
    this.state = 'joined';
    const format = formatFor(room);
    this.encoder = new SnapshotEncoder(format);
    const dynamicBodies = this.liveDynamicDescriptors(room);
    this.encoder.markDescriptorsKnown(dynamicBodies.map((d) => d.id));
    this.send({
      type: 'welcome',
      protocolVersion: PROTOCOL_VERSION,
      playerId: joined.playerId,
      roomId: room.id,
      tick: room.sim.tick,
      tickRateHz: 60,
      snapshotRateHz: room.snapshotRateHz,
      scenario: { name: room.scenarioName, description: room.description, params: { ...room.params }, bounds: room.bounds },
      snapshotFormat: snapshotFormatSpec(format),
      staticBodies: room.staticDescriptors(),
      dynamicBodies,
    });
    this.ctx.logger.info({ session: this.id, remote: this.conn.remote, room: room.id, playerId: joined.playerId, name }, 'player joined');
  }

  /** Every live body snapshots will carry: non-static ones and statics spawned after the scene was built. */
  private liveDynamicDescriptors(room: Room): BodyDescriptor[] {
    const read = room.sim.readBodyStates();
    const out: BodyDescriptor[] = [];
    for (let i = 0; i < read.count; i++) {
      if (room.isSceneStatic(read.ids[i])) continue;
      const d = room.sim.bodyDescriptor(read.ids[i]);
      if (d) out.push(d);
    }
    return out;
  }

  private joinFailed(error: unknown): void {
    if (this.state === 'closed') return;
    const code = error instanceof RoomError ? error.code : ErrorCode.Internal;
    const message = error instanceof Error ? error.message : String(error);
    if (!(error instanceof RoomError)) this.ctx.logger.error({ session: this.id, err: error }, 'joining a room failed');
    const bye = code === ErrorCode.RoomFull ? ByeReason.RoomFull : code === ErrorCode.ServerFull ? ByeReason.ServerFull : code === ErrorCode.RoomNotFound ? ByeReason.RoomNotFound : ByeReason.Kicked;
    this.sendError(code, message);
    this.end(bye, message, CloseCode.TryAgainLater);
  }

  /** Answers a refused message with an error; too many in a short time disconnect the client. */
  private refuse(code: ErrorCode, message: string): void {
    this.stats.badMessages++;
    this.ctx.metrics.badMessages.inc({ reason: code });
    if (!this.badLimiter.take()) {
      this.end(ByeReason.TooManyErrors, `too many invalid messages (last: ${message})`, CloseCode.PolicyViolation);
      return;
    }
    this.sendError(code, message);
  }

  private sendError(code: ErrorCode, message: string): void {
    this.stats.errorsSent++;
    this.send({ type: 'error', code, message: message.slice(0, 300) });
  }

  private send(msg: ServerMessage): number {
    if (this.state === 'closed' || !this.conn.isOpen()) return 0;
    return this.sendEncoded(encodeServerMessage(msg));
  }

  /** Sends an already framed server message (shared between clients; never mutated). */
  private sendEncoded(bytes: Uint8Array): number {
    if (this.state === 'closed' || !this.conn.isOpen()) return 0;
    this.conn.send(bytes);
    this.stats.bytesSent += bytes.length;
    this.ctx.metrics.bytesSent.inc(bytes.length);
    return bytes.length;
  }

  /** Reliable delivery of one tick's events (RoomMember). */
  deliverEvents(_tick: number, events: readonly SimEvent[]): void {
    if (this.state !== 'joined') return;
    if (this.tooFarBehind()) return;
    // The room hands every member the same list: frame it once per tick, not once per client.
    let message = eventMessages.get(events);
    if (message === undefined) {
      message = encodeServerMessage({ type: 'events', events: events as SimEvent[] });
      eventMessages.set(events, message);
    }
    this.sendEncoded(message);
  }

  /** A snapshot for this client, unless its socket is backed up (RoomMember). */
  deliverFrame(frame: WorldFrame): void {
    if (this.state !== 'joined' || !this.encoder || !this.room) return;
    if (this.tooFarBehind()) return;
    const m = this.ctx.metrics;
    // A full snapshot is on its way and not acked yet: another full one would only repeat it.
    if (!this.encoder.shouldSend(frame.tick)) return;
    if (this.conn.bufferedAmount() > this.ctx.limits.snapshotSkipBufferedBytes) {
      this.stats.snapshotsSkipped++;
      m.snapshotsSkipped.inc();
      return;
    }
    const room = this.room;
    let q = frame.cache.get('quantized') as QuantizedFrame | undefined;
    if (!q) {
      // Bodies whose pose has not changed since the room's previous frame keep its integers (one format per room).
      const last = lastQuantized.get(room);
      const previous = last !== undefined && last.frame.tick < frame.tick ? { read: last.bodies, frame: last.frame } : undefined;
      q = quantizeFrame(this.encoder.format, frame.tick, frame.bodies, frame.characters, { includeStatic: (id) => !room.isSceneStatic(id), previous });
      frame.cache.set('quantized', q);
      lastQuantized.set(room, { bodies: frame.bodies, frame: q });
    }
    let shared = frame.cache.get('snapshotWork') as SharedFrameWork | undefined;
    if (!shared) {
      shared = new SharedFrameWork();
      frame.cache.set('snapshotWork', shared);
    }
    const encoded = this.encoder.encode(q, (id) => room.sim.bodyDescriptor(id) ?? undefined, shared);
    // Clients that share a baseline and the spawned bodies they still lack get the very same message: frame it once
    // per tick, baseline and descriptor set (a descriptor is the same object for every client within a tick).
    let key = `snapshotMessage:${encoded.baselineTick ?? -1}`;
    for (const d of encoded.descriptors) key += `,${d.id}`;
    let message = frame.cache.get(key) as Uint8Array | undefined;
    if (!message) {
      message = encodeServerMessage({ type: 'snapshot', bytes: encoded.bytes, descriptors: encoded.descriptors });
      frame.cache.set(key, message);
    }
    const size = this.sendEncoded(message);
    this.stats.snapshotsSent++;
    this.stats.snapshotBytes += size;
    m.snapshotBytes.observe(size);
    m.snapshotsSent.inc({ kind: encoded.baselineTick === null ? 'full' : 'delta' });
  }

  /** The room dropped this client after a failed delivery (RoomMember). */
  removed(reason: string): void {
    this.room = null;
    this.end(ByeReason.Kicked, reason, CloseCode.InternalError);
  }

  /** The room closed under this client (RoomMember). */
  roomClosed(reason: string): void {
    this.room = null;
    this.end(ByeReason.RoomClosed, reason, CloseCode.GoingAway);
  }

  /** Reliable messages may not be dropped; a client this far behind is disconnected instead of queued for. */
  private tooFarBehind(): boolean {
    const queued = this.conn.bufferedAmount();
    if (queued <= this.ctx.limits.maxBufferedBytes) return false;
    this.end(ByeReason.Timeout, `connection too slow: ${queued} bytes waiting to be sent`, CloseCode.TryAgainLater);
    return true;
  }

  /** Ends the session: bye with the reason (when the link is up), close, leave the room. Idempotent. */
  end(reason: ByeReason, message: string, code: number = CloseCode.Normal): void {
    if (this.state === 'closed') return;
    if (reason !== ByeReason.ClientBye) this.send({ type: 'bye', reason, message });
    // Misbehaviour (not a slow link or a full room): the transport stops reading the client and remembers its address.
    if (reason === ByeReason.Flood || reason === ByeReason.TooManyErrors || (reason === ByeReason.Timeout && this.state === 'hello')) this.conn.kicked?.(reason);
    if (reason !== ByeReason.ClientBye && reason !== ByeReason.ServerShutdown && reason !== ByeReason.RoomClosed) {
      this.ctx.metrics.disconnects.inc({ reason });
      this.ctx.logger.info({ session: this.id, remote: this.conn.remote, reason, message }, 'disconnecting client');
    }
    this.finish();
    this.conn.close(code, `${reason}: ${message}`);
  }

  private onClosed(code: number, reason: string): void {
    if (this.state === 'closed') return;
    if (code === CloseCode.MessageTooBig) {
      this.stats.badMessages++;
      this.ctx.metrics.badMessages.inc({ reason: ErrorCode.Oversize });
      this.ctx.metrics.disconnects.inc({ reason: ErrorCode.Oversize });
    }
    this.ctx.logger.debug({ session: this.id, code, reason }, 'connection closed by peer');
    this.finish();
  }

  private finish(): void {
    if (this.state === 'closed') return;
    const wasJoined = this.state === 'joined';
    this.state = 'closed';
    if (this.helloTimer) this.ctx.clock.clearTimer(this.helloTimer);
    this.helloTimer = null;
    if (wasJoined && this.room) {
      this.ctx.logger.info({ session: this.id, room: this.room.id, playerId: this.playerId }, 'player left');
      this.room.leave(this.playerId);
    }
    this.room = null;
    this.ctx.metrics.clients.dec();
    this.ctx.onEnd(this);
  }
}
