// WebSocket side of the shared HTTP(S) port: admits upgrades through the connection policy (per-address caps, back-off
// after kicks), upgrades with `ws` (maxPayload enforced, no compression), wraps each socket as a ServerConnection
// whose sends within one turn of the event loop leave as one buffer in one write (a room's tick: events + snapshot,
// framed here, one syscall per socket), keeps links alive with pings, and makes sure a socket the server closes is
// gone shortly after.
import type { IncomingMessage, Server as HttpServer } from 'node:http';
import type { Server as HttpsServer } from 'node:https';
import type { Duplex } from 'node:stream';
import { WebSocketServer, type RawData, type WebSocket } from 'ws';
import type { Clock, TimerHandle } from '../shared/clock.ts';
import { refuseUpgrade, type Refusal as AccessRefusal } from './access/refusal.ts';
import { addressKey, clientAddress, describeAddress } from './client-address.ts';
import { clampCloseReason, CloseCode, type ConnectionHandlers, type ServerConnection } from './connection.ts';
import { ConnectionPolicy, RefusalReason, type ConnectionTicket, type Refusal } from './connection-policy.ts';
import type { Logger } from './logger.ts';
import type { ServerMetrics } from './metrics.ts';
import { refusalResponse, Tarpit } from './tcp-gate.ts';
import { frameHeaderBytes, FrameWriter } from './ws-frames.ts';

/** Options of attachWsGateway. */
export interface WsGatewayOptions {
  clock: Clock;
  /** Largest incoming message in bytes; bigger frames close the socket with 1009. */
  maxPayloadBytes: number;
  /** Milliseconds between keep-alive pings; a socket that missed one pong is terminated. Default 15000. */
  heartbeatMs?: number;
  /** How long a socket the server closed may take to finish the close handshake before it is destroyed. Default 1000. */
  closeGraceMs?: number;
  /** Who may connect (default: a policy with the default limits on `clock`). */
  policy?: ConnectionPolicy;
  /** Where refused sockets of one address wait for their answer (default: a tarpit with the default limits). */
  tarpit?: Tarpit;
  /** Read the client's address from X-Forwarded-For (only behind a reverse proxy). Default false. */
  trustProxy?: boolean;
  /** Refusals and keep-alive disconnects are counted here when given. */
  metrics?: ServerMetrics;
  logger?: Logger;
  /** Called for each accepted socket. */
  onConnection(conn: ServerConnection, req: IncomingMessage): void;
  /** Returns a reason to refuse new sockets (shutting down, full), or null to accept. */
  refuse?(): string | null;
  /** Access rules for this upgrade request (the Origin check): a refusal is answered instead of upgrading. */
  checkUpgrade?(req: IncomingMessage): AccessRefusal | null;
}

/** The running gateway. */
export interface WsGateway {
  /** Stops accepting sockets and terminates any that are still open after `graceMs`. */
  close(graceMs?: number): Promise<void>;
  /** Sockets currently open (past the upgrade). */
  openSockets(): number;
  /** The policy admitting sockets. */
  readonly policy: ConnectionPolicy;
}

// A Buffer is a Uint8Array already: handed on as it is (a view made per message showed in profiles of crowded rooms).
function toBytes(data: RawData): Uint8Array {
  if (Array.isArray(data)) return Buffer.concat(data);
  if (data instanceof ArrayBuffer) return new Uint8Array(data);
  return data;
}

/** A ws socket as a ServerConnection. */
class WsConnection implements ServerConnection {
  readonly remote: string;
  private readonly socket: WebSocket;
  /** The TCP (or TLS) socket under `socket`: this turn's messages are written to it as one buffer of frames. */
  private readonly raw: Duplex;
  /** Messages sent in this turn of the event loop, and their bytes framed: written by `flush` (a microtask). */
  private readonly pending: Uint8Array[] = [];
  private pendingBytes = 0;
  private readonly ticket: ConnectionTicket;
  private readonly clock: Clock;
  private readonly closeGraceMs: number;
  private handlers: ConnectionHandlers | null = null;
  private early: Array<[Uint8Array, boolean]> = [];
  private closedNotified = false;
  private earlyClose: [number, string] | null = null;
  private errorClose: [number, string] | null = null;
  private killTimer: TimerHandle | null = null;
  alive = true;

  /** The gateway's framing scratch (shared: flushes run one at a time). */
  private readonly frames: FrameWriter;

  constructor(socket: WebSocket, raw: Duplex, remote: string, ticket: ConnectionTicket, clock: Clock, closeGraceMs: number, frames: FrameWriter) {
    this.frames = frames;
    this.socket = socket;
    this.raw = raw;
    this.remote = remote;
    this.ticket = ticket;
    this.clock = clock;
    this.closeGraceMs = closeGraceMs;
    socket.on('message', (data, isBinary) => {
      if (socket.readyState !== socket.OPEN) return; // closing: nothing the peer says matters any more
      const bytes = toBytes(data);
      if (this.handlers) this.handlers.message(bytes, isBinary);
      else this.early.push([bytes, isBinary]);
    });
    socket.on('pong', () => {
      this.alive = true;
    });
    // ws reports protocol violations (oversize frame, bad framing) as 'error' and closes the socket itself; the
    // close event then carries the peer's echo (or 1006), so remember why ws closed it. Both are a client's fault.
    socket.on('error', (err: Error & { code?: string }) => {
      if (this.errorClose) return;
      this.errorClose = err.code === 'WS_ERR_UNSUPPORTED_MESSAGE_LENGTH' ? [CloseCode.MessageTooBig, 'message too big'] : [CloseCode.ProtocolError, err.message];
      ticket.kicked();
      this.destroyLater();
    });
    socket.on('close', (code, reason) => {
      if (this.killTimer) this.clock.clearTimer(this.killTimer);
      this.killTimer = null;
      if (this.errorClose) this.notifyClose(this.errorClose[0], this.errorClose[1]);
      else this.notifyClose(code, reason.toString('utf8'));
    });
  }

  private notifyClose(code: number, reason: string): void {
    if (this.closedNotified) return;
    if (!this.handlers) {
      this.earlyClose = [code, reason];
      return;
    }
    this.closedNotified = true;
    this.handlers.close(code, reason);
  }

  /** The close handshake gets closeGraceMs; then the socket is cut (ws alone would wait 30 s, reading all along). */
  private destroyLater(): void {
    if (this.killTimer) return;
    this.killTimer = this.clock.setTimer(this.closeGraceMs, () => {
      this.killTimer = null;
      this.socket.terminate();
    });
  }

  /**
   * Queues one message. The first send of a turn schedules a microtask that frames everything sent to this client in
   * that synchronous run (a room tick's events and snapshot, a worker batch) into one buffer and writes it: one write
   * call and one syscall, and nothing waits past the current turn. (`ws`'s own send would make a header buffer and
   * two corked writes per message, then a writev.)
   */
  send(data: Uint8Array): void {
    if (this.socket.readyState !== this.socket.OPEN) return;
    if (this.pending.length === 0) queueMicrotask(this.flush);
    this.pending.push(data);
    this.pendingBytes += frameHeaderBytes(data.length) + data.length;
  }

  private readonly flush = (): void => {
    if (this.pending.length === 0) return;
    // Nothing may follow a close frame: once ws has answered the peer's (or the socket is gone), the turn's messages
    // are dropped, as ws drops what is sent to a socket that is no longer open.
    if (this.socket.readyState === this.socket.OPEN && !this.raw.destroyed) {
      this.raw.write(this.frames.frame(this.pending, this.pendingBytes));
      // Bytes left queued in the stream (the kernel did not take them all at once) still point into the scratch.
      if (this.raw.writableLength > 0) this.frames.handOff();
    }
    this.pending.length = 0;
    this.pendingBytes = 0;
  };

  bufferedAmount(): number {
    return this.socket.bufferedAmount + this.pendingBytes;
  }

  isOpen(): boolean {
    return this.socket.readyState === this.socket.OPEN;
  }

  close(code: number, reason: string): void {
    if (this.socket.readyState === this.socket.CLOSED || this.socket.readyState === this.socket.CLOSING) return;
    this.flush(); // what was sent this turn (a bye) goes before the close frame
    this.socket.close(code, clampCloseReason(reason));
    this.destroyLater();
  }

  helloed(): void {
    this.ticket.helloed();
  }

  kicked(): void {
    this.ticket.kicked();
    // Not another byte from a client being kicked: its bye and close frame go out, then it is cut after the grace.
    this.socket.pause();
    this.destroyLater();
  }

  terminate(): void {
    this.socket.terminate();
  }

  ping(): void {
    this.socket.ping();
  }

  attach(handlers: ConnectionHandlers): void {
    this.handlers = handlers;
    const early = this.early;
    this.early = [];
    for (const [bytes, binary] of early) handlers.message(bytes, binary);
    if (this.earlyClose) this.notifyClose(this.earlyClose[0], this.earlyClose[1]);
  }
}

/** Handles WebSocket upgrades on `http` and hands every accepted socket to `onConnection`. */
export function attachWsGateway(http: HttpServer | HttpsServer, opts: WsGatewayOptions): WsGateway {
  const wss = new WebSocketServer({ noServer: true, maxPayload: opts.maxPayloadBytes, perMessageDeflate: false, clientTracking: false });
  const policy = opts.policy ?? new ConnectionPolicy(opts.clock);
  const tarpit = opts.tarpit ?? new Tarpit(opts.clock);
  const open = new Set<WsConnection>();
  const frames = new FrameWriter();
  const heartbeatMs = opts.heartbeatMs ?? 15_000;
  const closeGraceMs = opts.closeGraceMs ?? 1000;
  const trustProxy = opts.trustProxy ?? false;
  let closing = false;
  let heartbeat: TimerHandle | null = null;

  // Refusals for the whole server are answered at once; those for one address wait in the tarpit (bounded), so an
  // address that reconnects the moment it is refused cannot make us parse upgrades as fast as it can send them.
  const refuse = (socket: Duplex, key: string, refusal: Refusal | { reason: 'shutting-down' | 'server-full'; message: string; retryAfterMs: number | null }): void => {
    opts.metrics?.connectionsRefused.inc({ reason: refusal.reason });
    if (refusal.reason === RefusalReason.ServerFull || refusal.reason === 'shutting-down') {
      socket.end(refusalResponse(503, refusal.reason, refusal.message, refusal.retryAfterMs), () => socket.destroy());
      return;
    }
    tarpit.refuse(socket, key, refusal.retryAfterMs ?? 0, refusalResponse(429, 'rate-limited', refusal.message, refusal.retryAfterMs));
  };

  const onUpgrade = (req: IncomingMessage, socket: Duplex, head: Buffer): void => {
    socket.on('error', () => socket.destroy());
    // Access control first: a page from a refused origin gets its 403 before it costs a slot.
    const denied = opts.checkUpgrade?.(req) ?? null;
    if (denied !== null) {
      refuseUpgrade(socket, denied);
      return;
    }
    const client = clientAddress(req, trustProxy);
    const key = addressKey(client.address);
    if (closing) return refuse(socket, key, { reason: 'shutting-down', message: 'server shutting down', retryAfterMs: null });
    const server = opts.refuse?.() ?? null;
    if (server !== null) return refuse(socket, key, { reason: 'server-full', message: server, retryAfterMs: 5_000 });
    const refusal = policy.admit(key);
    if (refusal !== null) return refuse(socket, key, refusal);
    // Counted from here until the TCP socket is gone, whatever happens to the handshake or the session.
    const ticket = policy.open(key);
    socket.once('close', () => ticket.closed());
    wss.handleUpgrade(req, socket, head, (ws) => {
      const conn = new WsConnection(ws, socket, describeAddress(client), ticket, opts.clock, closeGraceMs, frames);
      open.add(conn);
      ws.on('close', () => open.delete(conn));
      opts.onConnection(conn, req);
    });
  };
  http.on('upgrade', onUpgrade);

  const beat = (): void => {
    for (const conn of open) {
      if (!conn.alive) {
        opts.metrics?.disconnects.inc({ reason: 'keepalive-timeout' });
        opts.logger?.info({ remote: conn.remote }, 'disconnecting client: no pong to the last keep-alive ping');
        conn.terminate();
        continue;
      }
      conn.alive = false;
      try {
        conn.ping();
      } catch {
        conn.terminate();
      }
    }
    policy.sweep();
    heartbeat = opts.clock.setTimer(heartbeatMs, beat);
  };
  heartbeat = opts.clock.setTimer(heartbeatMs, beat);

  return {
    policy,
    openSockets: () => open.size,
    close: async (graceMs = 1000) => {
      closing = true;
      tarpit.close();
      http.off('upgrade', onUpgrade);
      if (heartbeat) opts.clock.clearTimer(heartbeat);
      heartbeat = null;
      for (const conn of open) conn.close(CloseCode.GoingAway, 'server shutting down');
      // Give peers a moment to answer the close handshake, then cut whatever is left.
      const deadline = performance.now() + graceMs;
      while (open.size > 0 && performance.now() < deadline) await new Promise((resolve) => setTimeout(resolve, 5));
      for (const conn of open) conn.terminate();
      open.clear();
      await new Promise<void>((resolve) => wss.close(() => resolve()));
    },
  };
}
