// The listening socket in front of the HTTP(S) server: a connection from an address in back-off (its clients kept
// getting kicked) is held unread for a moment, answered 429 and closed, before any HTTP parsing; everything else goes
// on to the HTTP server. Holding refused connections (the tarpit) caps how fast a reconnect loop can cost us work.
import type { Server as HttpServer } from 'node:http';
import type { Server as HttpsServer } from 'node:https';
import { createServer, type Server, type Socket } from 'node:net';
import type { Duplex } from 'node:stream';
import { addressKey, normalizeAddress } from './client-address.ts';
import type { Clock } from '../shared/clock.ts';
import type { ConnectionPolicy } from './connection-policy.ts';
import { rawErrorResponse } from './http-errors.ts';
import type { ServerMetrics } from './metrics.ts';

/** Limits of the tarpit. */
export interface TarpitOptions {
  /** Longest a refused connection is held before its answer. Default 2000 ms. */
  holdMs?: number;
  /** Most refused connections held at once from one address (IPv6: /64); past it they are cut at once. Default 256. */
  maxPerAddress?: number;
  /** Most refused connections held at once in all (each holds a file descriptor). Default 1024. */
  maxHeld?: number;
}

/** Holds refused connections for a while, then writes their answer and closes them; bounded per address and in all. */
export class Tarpit {
  private readonly clock: Clock;
  private readonly holdMs: number;
  private readonly maxPerAddress: number;
  private readonly maxHeld: number;
  private readonly perAddress = new Map<string, number>();
  private readonly sockets = new Set<Duplex>();
  private held = 0;

  constructor(clock: Clock, opts: TarpitOptions = {}) {
    this.clock = clock;
    this.holdMs = opts.holdMs ?? 2000;
    this.maxPerAddress = opts.maxPerAddress ?? 256;
    this.maxHeld = opts.maxHeld ?? 1024;
  }

  /** Connections held now. */
  get size(): number {
    return this.held;
  }

  /**
   * Answers `socket` with `response` after min(waitMs, holdMs) and closes it, not reading it meanwhile. When the
   * tarpit is full (for this address or in all) the socket is cut at once without an answer: the cheapest refusal.
   */
  refuse(socket: Duplex, key: string, waitMs: number, response: string): void {
    const n = this.perAddress.get(key) ?? 0;
    const finish = (): void => {
      if (!socket.destroyed) socket.end(response, () => socket.destroy());
    };
    if (waitMs <= 0 || this.holdMs <= 0) {
      finish();
      return;
    }
    if (n >= this.maxPerAddress || this.held >= this.maxHeld) {
      socket.destroy();
      return;
    }
    this.perAddress.set(key, n + 1);
    this.held++;
    this.sockets.add(socket);
    socket.pause();
    let released = false;
    const release = (): void => {
      if (released) return;
      released = true;
      this.sockets.delete(socket);
      this.held--;
      const left = (this.perAddress.get(key) ?? 1) - 1;
      if (left === 0) this.perAddress.delete(key);
      else this.perAddress.set(key, left);
    };
    socket.once('close', release);
    this.clock.setTimer(Math.min(waitMs, this.holdMs), () => {
      release();
      finish();
    });
  }

  /** Cuts every held connection now (shutdown). */
  close(): void {
    for (const socket of [...this.sockets]) socket.destroy();
  }
}

/** A refusal as a raw HTTP/1.1 response in the API's `{error, message}` shape. */
export function refusalResponse(status: 429 | 503, code: string, message: string, retryAfterMs: number | null): string {
  return rawErrorResponse(status, code, message, retryAfterMs === null ? {} : { 'Retry-After': String(Math.max(1, Math.ceil(retryAfterMs / 1000))) });
}

/** Options of createTcpGate. */
export interface TcpGateOptions {
  policy: ConnectionPolicy;
  tarpit: Tarpit;
  /** Behind a reverse proxy every connection comes from the proxy: then the gate lets everything through. */
  trustProxy: boolean;
  metrics?: ServerMetrics;
}

/** A net.Server to listen with instead of `target`: it hands every admitted connection to `target`. */
export function createTcpGate(target: HttpServer | HttpsServer, opts: TcpGateOptions): Server {
  // The same socket settings Node's HTTP server uses (no Nagle delay: snapshots go out as they are written).
  return createServer({ pauseOnConnect: true, allowHalfOpen: true, noDelay: true }, (socket: Socket) => {
    socket.on('error', () => socket.destroy());
    if (!opts.trustProxy) {
      const key = addressKey(normalizeAddress(socket.remoteAddress ?? 'unknown'));
      const waitMs = opts.policy.backoffRemainingMs(key);
      if (waitMs > 0) {
        opts.metrics?.connectionsRefused.inc({ reason: 'backoff' });
        const message = `too many clients from your address were disconnected for misbehaving; try again in ${Math.ceil(waitMs / 1000)} s`;
        opts.tarpit.refuse(socket, key, waitMs, refusalResponse(429, 'rate-limited', message, waitMs));
        return;
      }
    }
    target.emit('connection', socket);
    socket.resume();
  });
}
