// WebSocket side of the shared HTTP port: upgrades requests with `ws` (maxPayload enforced, no compression), wraps
// each socket as a ServerConnection, and keeps links alive with ws pings (dead peers are terminated).
import type { IncomingMessage, Server as HttpServer } from 'node:http';
import type { Duplex } from 'node:stream';
import { WebSocketServer, type RawData, type WebSocket } from 'ws';
import type { Clock, TimerHandle } from '../shared/clock.ts';
import { refuseUpgrade, type Refusal } from './access/refusal.ts';
import { clampCloseReason, CloseCode, type ConnectionHandlers, type ServerConnection } from './connection.ts';

/** Options of attachWsGateway. */
export interface WsGatewayOptions {
  clock: Clock;
  /** Largest incoming message in bytes; bigger frames close the socket with 1009. */
  maxPayloadBytes: number;
  /** Milliseconds between keep-alive pings; a socket that missed one pong is terminated. Default 15000. */
  heartbeatMs?: number;
  /** Called for each accepted socket. */
  onConnection(conn: ServerConnection, req: IncomingMessage): void;
  /** Returns a reason to refuse new sockets (shutting down, full), or null to accept. */
  refuse?(): string | null;
  /** Access rules for this upgrade request (the Origin check): a refusal is answered instead of upgrading. */
  checkUpgrade?(req: IncomingMessage): Refusal | null;
}

/** The running gateway. */
export interface WsGateway {
  /** Stops accepting sockets and terminates any that are still open after `graceMs`. */
  close(graceMs?: number): Promise<void>;
  /** Sockets currently open. */
  openSockets(): number;
}

function toBytes(data: RawData): Uint8Array {
  if (Array.isArray(data)) return new Uint8Array(Buffer.concat(data));
  if (data instanceof ArrayBuffer) return new Uint8Array(data);
  return new Uint8Array(data.buffer, data.byteOffset, data.byteLength);
}

/** A ws socket as a ServerConnection. */
class WsConnection implements ServerConnection {
  readonly remote: string;
  private readonly socket: WebSocket;
  private handlers: ConnectionHandlers | null = null;
  private early: Array<[Uint8Array, boolean]> = [];
  private closedNotified = false;
  private earlyClose: [number, string] | null = null;
  private errorClose: [number, string] | null = null;
  alive = true;

  constructor(socket: WebSocket, remote: string) {
    this.socket = socket;
    this.remote = remote;
    socket.on('message', (data, isBinary) => {
      const bytes = toBytes(data);
      if (this.handlers) this.handlers.message(bytes, isBinary);
      else this.early.push([bytes, isBinary]);
    });
    socket.on('pong', () => {
      this.alive = true;
    });
    // ws reports protocol violations (oversize frame, bad framing) as 'error' and closes the socket itself; the
    // close event then carries the peer's echo (or 1006), so remember why ws closed it.
    socket.on('error', (err: Error & { code?: string }) => {
      this.errorClose ??= err.code === 'WS_ERR_UNSUPPORTED_MESSAGE_LENGTH' ? [CloseCode.MessageTooBig, 'message too big'] : [CloseCode.ProtocolError, err.message];
    });
    socket.on('close', (code, reason) => {
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

  send(data: Uint8Array): void {
    if (this.socket.readyState !== this.socket.OPEN) return;
    this.socket.send(data, { binary: true });
  }

  bufferedAmount(): number {
    return this.socket.bufferedAmount;
  }

  isOpen(): boolean {
    return this.socket.readyState === this.socket.OPEN;
  }

  close(code: number, reason: string): void {
    if (this.socket.readyState === this.socket.CLOSED || this.socket.readyState === this.socket.CLOSING) return;
    this.socket.close(code, clampCloseReason(reason));
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
export function attachWsGateway(http: HttpServer, opts: WsGatewayOptions): WsGateway {
  const wss = new WebSocketServer({ noServer: true, maxPayload: opts.maxPayloadBytes, perMessageDeflate: false, clientTracking: false });
  const open = new Set<WsConnection>();
  const heartbeatMs = opts.heartbeatMs ?? 15_000;
  let closing = false;
  let heartbeat: TimerHandle | null = null;

  const onUpgrade = (req: IncomingMessage, socket: Duplex, head: Buffer): void => {
    socket.on('error', () => socket.destroy());
    const denied = opts.checkUpgrade?.(req) ?? null;
    if (denied !== null) {
      refuseUpgrade(socket, denied);
      return;
    }
    const refusal = closing ? 'server shutting down' : (opts.refuse?.() ?? null);
    if (refusal !== null) {
      socket.end(`HTTP/1.1 503 Service Unavailable\r\nContent-Type: text/plain\r\nConnection: close\r\n\r\n${refusal}\n`);
      return;
    }
    wss.handleUpgrade(req, socket, head, (ws) => {
      const remote = `${req.socket.remoteAddress ?? '?'}:${req.socket.remotePort ?? '?'}`;
      const conn = new WsConnection(ws, remote);
      open.add(conn);
      ws.on('close', () => open.delete(conn));
      opts.onConnection(conn, req);
    });
  };
  http.on('upgrade', onUpgrade);

  const beat = (): void => {
    for (const conn of open) {
      if (!conn.alive) {
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
    heartbeat = opts.clock.setTimer(heartbeatMs, beat);
  };
  heartbeat = opts.clock.setTimer(heartbeatMs, beat);

  return {
    openSockets: () => open.size,
    close: async (graceMs = 1000) => {
      closing = true;
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
