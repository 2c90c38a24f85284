// One client connection from hello to bye: validates every incoming frame, enforces per-client rate and error limits,
// enters a room (or resumes a held player) wherever it runs, hands a joined player's messages to its PlayerInbox, and is the
// MemberSink the room's bytes for this client arrive at. Nothing a client sends reaches the room unvalidated or under
// another player's id.
import type { TimerHandle } from '../shared/clock.ts';
import { ByeReason, decodeClientMessage, encodeServerMessage, ErrorCode, NetMode, type ClientMessage, type HelloMessage, type ServerMessage } from '../shared/protocol/index.ts';
import { admitSeat } from './access/admission.ts';
import type { ResumeHolder } from './access/resume-tokens.ts';
import { CloseCode, type ServerConnection } from './connection.ts';
import { DeliveryKind, type HostedRoom, type MemberSink, type RoomEntry, type Seat } from './hosted-room.ts';
import { PlayerInbox, pongFor, type InboxVerdict } from './player-inbox.ts';
import { RateLimiter } from './rate-limiter.ts';
import { RoomMovedError } from './fleet/room-moved.ts';
import { RoomError } from './room.ts';
import { LinkStats, snapshotTick } from './monitor/link-stats.ts';
import type { SessionContext, SessionStats } from './session-context.ts';

let nextSessionId = 1;

/** How a joined player's session ended: leave the room, or be held for a reconnect (the link dropped). */
type Ending = 'leave' | 'hold';

/** One connected client. */
export class ClientSession implements MemberSink, ResumeHolder {
  readonly id = nextSessionId++;
  readonly conn: ServerConnection;
  readonly stats: SessionStats = { messagesReceived: 0, badMessages: 0, errorsSent: 0, snapshotsSent: 0, snapshotsSkipped: 0, snapshotBytes: 0, bytesSent: 0, inputsLate: 0, inputsTooFar: 0 };
  /** Name, bytes in, input lead and RTT, for the monitor. */
  readonly link = new LinkStats();
  private readonly ctx: SessionContext;
  private readonly messageLimiter: RateLimiter;
  private readonly badLimiter: RateLimiter;
  private state: 'hello' | 'joining' | 'joined' | 'closed' = 'hello';
  private helloTimer: TimerHandle | null;
  private room: HostedRoom | null = null;
  private playerId = 0;
  /** The joined player's seat and what its messages do to it (null before the welcome). */
  private inbox: PlayerInbox | null = null;
  /** The seat this session's hello used, until the join it was for succeeds (given back if it fails). */
  private seatId: string | null = null;

  constructor(conn: ServerConnection, ctx: SessionContext) {
    this.conn = conn;
    this.ctx = ctx;
    this.messageLimiter = new RateLimiter(ctx.clock, ctx.limits.messages);
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

  /** Ticks the room simulated with this player's previous input repeated (none had arrived); 0 before joining. */
  missedInputTicks(): number {
    return this.inbox ? this.inbox.seat.missedInputTicks() : 0;
  }

  /** The room once joined. */
  get currentRoom(): HostedRoom | null {
    return this.room;
  }

  /** Whether the session has ended. */
  get ended(): boolean {
    return this.state === 'closed';
  }

  private onMessage(data: Uint8Array, binary: boolean): void {
    if (this.state === 'closed') return;
    try {
      this.receive(data, binary);
    } catch (error) {
      this.failed(error);
    }
  }

  private receive(data: Uint8Array, binary: boolean): void {
    const m = this.ctx.metrics;
    this.stats.messagesReceived++;
    m.messagesReceived.inc();
    m.bytesReceived.inc(data.length);
    this.link.bytesIn += data.length;
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
      if (decoded.code === ErrorCode.VersionMismatch && this.state === 'hello') {
        this.sendError(decoded.code, decoded.error);
        this.end(ByeReason.VersionMismatch, decoded.error, CloseCode.PolicyViolation);
        return;
      }
      this.refuse(decoded.code, decoded.error);
      return;
    }
    if (decoded.clampedCommands > 0) m.inputsClamped.inc(decoded.clampedCommands);
    this.handle(decoded.message);
  }

  /**
   * An exception while taking one of this client's messages (decoding or handling: a server bug, whatever the
   * client sent) is that client's protocol error: an error and a bye, one log line, a count; never the room's or
   * the process's problem. The session is closed, so nothing it sends afterwards is read or logged again.
   */
  private failed(error: unknown): void {
    this.ctx.metrics.messageErrors.inc();
    this.ctx.logger.error({ session: this.id, remote: this.conn.remote, state: this.state, err: error }, 'handling a client message failed; disconnecting the client');
    try {
      this.sendError(ErrorCode.Internal, 'the server failed while handling your message');
      this.end(ByeReason.Kicked, 'internal error handling your message', CloseCode.InternalError);
    } catch {
      this.finish('leave'); // the link itself is broken: forget the client, the transport closes the socket
    }
  }

  private handle(msg: ClientMessage): void {
    switch (msg.type) {
      case 'hello':
        this.onHello(msg);
        return;
      case 'input':
        this.apply('input before the welcome', (inbox) => inbox.input(msg));
        return;
      case 'ack':
        this.apply('ack before the welcome', (inbox) => inbox.ack(msg.tick));
        return;
      case 'ping':
        this.send(pongFor(this.room ? (this.inbox?.seat ?? null) : null, this.ctx.clock, msg.clientTimeMs));
        return;
      case 'bye':
        this.end(ByeReason.ClientBye, 'goodbye', CloseCode.Normal);
        return;
      case 'resync':
        this.apply('resync is for clients served in predict mode', (inbox) => inbox.resync());
        return;
      case 'netMode':
        this.apply('netMode before the welcome', (inbox) => inbox.netMode(msg.mode));
        return;
      case 'game':
        this.apply('game message before the welcome', (inbox) => inbox.game(msg));
        return;
    }
  }

  /** Hands a message to the joined player's inbox and does what it says; before the welcome the message is refused. */
  private apply(early: string, take: (inbox: PlayerInbox) => InboxVerdict | void): void {
    if (this.state !== 'joined' || !this.inbox) {
      this.refuse(ErrorCode.UnexpectedMessage, early);
      return;
    }
    const verdict = take(this.inbox);
    if (!verdict) return;
    if ('flood' in verdict) this.end(ByeReason.Flood, verdict.flood, CloseCode.PolicyViolation);
    else this.refuse(verdict.refuse, verdict.message);
  }

  private onHello(hello: HelloMessage): void {
    if (this.state !== 'hello') {
      this.refuse(ErrorCode.UnexpectedMessage, 'hello was already received');
      return;
    }
    this.state = 'joining';
    if (this.helloTimer) this.ctx.clock.clearTimer(this.helloTimer);
    this.helloTimer = null;
    this.conn.helloed?.();
    this.link.name = hello.name;
    if (hello.resumeToken !== undefined) {
      const resume = this.ctx.access.resume;
      const claim = resume ? resume.claim(hello.resumeToken, hello.room) : ({ ok: false, reason: 'this server does not resume players' } as const);
      if (claim.ok) {
        this.enterRoom(claim.room, { resumePlayerId: claim.playerId });
        return;
      }
      // Not fatal: the client is told why and joins as a new player (under the same seat rules as anyone).
      this.ctx.metrics.accessRefused.inc({ reason: ErrorCode.ResumeRefused });
      this.sendError(ErrorCode.ResumeRefused, `cannot resume: ${claim.reason}; joining as a new player`);
    }
    const seat = admitSeat(this.ctx.access, hello.seatToken, hello.room);
    if (!seat.ok) {
      this.ctx.metrics.accessRefused.inc({ reason: seat.code });
      this.sendError(seat.code, seat.message);
      this.end(ByeReason.SeatRefused, seat.message, CloseCode.PolicyViolation);
      return;
    }
    this.seatId = seat.seatId;
    this.ctx.rooms
      .resolve(seat.roomId === null ? {} : { roomId: seat.roomId })
      .then(
        (room) => {
          if (this.state !== 'joining') {
            this.giveSeatBack(); // the client left while the room was being created
            return;
          }
          this.enterRoom(room, { name: hello.name });
        },
        (error: unknown) => this.joinFailed(error),
      )
      .catch((error: unknown) => this.failed(error)); // the welcome path is part of handling the hello
  }

  /** Enters a room as a new player or takes back a claimed one; the welcome goes out once the room has seated it. */
  private enterRoom(room: HostedRoom, entry: RoomEntry): void {
    room
      .enter(this, entry)
      .then(
        (seat) => {
          if (this.state !== 'joining') {
            room.leave(seat.playerId); // the client left while the room was seating it
            this.giveSeatBack();
            return;
          }
          this.seatId = null;
          this.seated(room, seat, entry);
        },
        (error: unknown) => this.joinFailed(error),
      )
      .catch((error: unknown) => this.failed(error));
  }

  private seated(room: HostedRoom, seat: Seat, entry: RoomEntry): void {
    const resumed = 'resumePlayerId' in entry;
    this.room = room;
    this.playerId = seat.playerId;
    this.inbox = new PlayerInbox(seat, { clock: this.ctx.clock, metrics: this.ctx.metrics, limits: this.ctx.limits, stats: this.stats, link: this.link });
    this.state = 'joined';
    const resume = this.ctx.access.resume;
    const token = resume ? resume.issue(room, seat.playerId, this) : null;
    const inputDelayTicks = seat.welcome.netMode === NetMode.Predict ? this.ctx.inputDelayTicks : 0;
    this.send({ ...seat.welcome, resumeToken: token, resumeGraceMs: resume ? resume.graceMs : 0, resumed, inputDelayTicks });
    if (resumed) {
      this.ctx.metrics.resumes.inc();
      this.ctx.logger.info({ session: this.id, remote: this.conn.remote, room: room.id, playerId: seat.playerId }, 'player resumed');
    } else {
      this.ctx.logger.info({ session: this.id, remote: this.conn.remote, room: room.id, playerId: seat.playerId, name: 'name' in entry ? entry.name : undefined }, 'player joined');
    }
  }

  private giveSeatBack(): void {
    if (this.seatId !== null) this.ctx.access.seats?.release(this.seatId);
    this.seatId = null;
  }

  private joinFailed(error: unknown): void {
    this.giveSeatBack();
    if (this.state === 'closed') return;
    const code = error instanceof RoomError ? error.code : ErrorCode.Internal;
    const message = error instanceof Error ? error.message : String(error);
    if (!(error instanceof RoomError)) this.ctx.logger.error({ session: this.id, err: error }, 'joining a room failed');
    this.sendError(code, message);
    if (error instanceof RoomMovedError) {
      this.end(ByeReason.RoomMoved, message, CloseCode.Normal, error.host.wsUrl);
      return;
    }
    const bye = code === ErrorCode.RoomFull ? ByeReason.RoomFull : code === ErrorCode.ServerFull ? ByeReason.ServerFull : code === ErrorCode.RoomNotFound ? ByeReason.RoomNotFound : ByeReason.Kicked;
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

  /** One framed message from the room for this client (MemberSink). */
  deliver(bytes: Uint8Array, kind: DeliveryKind, knownTick?: number): void {
    if (this.state !== 'joined') return;
    const size = this.sendEncoded(bytes);
    if (kind === DeliveryKind.Snapshot && size > 0) {
      this.stats.snapshotsSent++;
      this.stats.snapshotBytes += size;
      const tick = knownTick ?? snapshotTick(bytes, this.link.lastSnapshotTick);
      if (tick !== null) this.link.snapshotSent(tick, this.ctx.clock.nowMs());
    }
  }

  /** The room skipped a snapshot for this client: its socket is backed up (MemberSink). */
  snapshotSkipped(): void {
    this.stats.snapshotsSkipped++;
  }

  /** Whether this client's socket is backed up past the snapshot threshold (MemberSink). */
  backedUp(): boolean {
    return this.conn.bufferedAmount() > this.ctx.limits.snapshotSkipBufferedBytes;
  }

  /** The room dropped this client after a failed delivery (MemberSink). */
  removed(reason: string): void {
    if (this.room) this.ctx.access.resume?.release(this.room, this.playerId, 'the server removed the player');
    this.room = null;
    this.end(ByeReason.Kicked, reason, CloseCode.InternalError);
  }

  /** The room closed under this client (MemberSink). */
  roomClosed(reason: string): void {
    this.room = null;
    this.end(ByeReason.RoomClosed, reason, CloseCode.GoingAway);
  }

  /** Another connection resumed this player (ResumeHolder): end this link without leaving the room. */
  replaced(): void {
    if (this.state === 'closed') return;
    this.room = null;
    this.end(ByeReason.Replaced, 'another connection resumed this player', CloseCode.Normal);
  }

  /** Reliable messages may not be dropped; a client this far behind is disconnected instead of queued for. */
  tooFarBehind(): boolean {
    const queued = this.conn.bufferedAmount();
    if (queued <= this.ctx.limits.maxBufferedBytes) return false;
    this.end(ByeReason.Timeout, `connection too slow: ${queued} bytes waiting to be sent`, CloseCode.TryAgainLater);
    return true;
  }

  /** Ends the session: bye with the reason (and `url` for room-moved) when the link is up, close, leave the room. Idempotent. */
  end(reason: ByeReason, message: string, code: number = CloseCode.Normal, url?: string): void {
    if (this.state === 'closed') return;
    if (reason !== ByeReason.ClientBye) this.send(url === undefined ? { type: 'bye', reason, message } : { type: 'bye', reason, message, url });
    // Misbehaviour (not a slow link or a full room): the transport stops reading the client and remembers its address.
    if (reason === ByeReason.Flood || reason === ByeReason.TooManyErrors || (reason === ByeReason.Timeout && this.state === 'hello')) this.conn.kicked?.(reason);
    if (reason !== ByeReason.ClientBye && reason !== ByeReason.ServerShutdown && reason !== ByeReason.RoomClosed && reason !== ByeReason.RoomMoved) {
      this.ctx.metrics.disconnects.inc({ reason });
      this.ctx.logger.info({ session: this.id, remote: this.conn.remote, reason, message }, 'disconnecting client');
    }
    // A link that timed out (or fell too far behind) may come back: its player is held like after a drop.
    this.finish(reason === ByeReason.Timeout ? 'hold' : 'leave');
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
    // A link that died without a close frame (network loss, a missed heartbeat) may come back: its player is held.
    // A close frame means the client's end closed on purpose (or the transport closed it for breaking the protocol).
    this.finish(code === CloseCode.Abnormal ? 'hold' : 'leave');
  }

  private finish(ending: Ending): void {
    if (this.state === 'closed') return;
    const wasJoined = this.state === 'joined';
    this.state = 'closed';
    if (this.helloTimer) this.ctx.clock.clearTimer(this.helloTimer);
    this.helloTimer = null;
    if (wasJoined && this.room) {
      const resume = this.ctx.access.resume;
      if (ending === 'hold' && resume !== null && resume.hold(this.room, this.playerId)) {
        this.ctx.logger.info({ session: this.id, room: this.room.id, playerId: this.playerId, graceMs: resume.graceMs }, 'player link dropped: held for a reconnect');
      } else {
        this.ctx.logger.info({ session: this.id, room: this.room.id, playerId: this.playerId }, 'player left');
        this.room.leave(this.playerId);
        resume?.release(this.room, this.playerId);
      }
    }
    this.room = null;
    this.ctx.metrics.clients.dec();
    this.ctx.onEnd(this);
  }
}
