// An in-memory network on a Clock for tests and tools: servers listen on URLs, clients connect through an ordinary
// TransportFactory; each direction delivers whole messages in order after latency plus seeded jitter (a TCP-like
// link conditioner). Peers can be dropped abruptly and URLs taken down to test reconnects.
import type { Clock } from '../shared/clock.ts';
import type { Transport, TransportFactory, TransportHandlers } from './transport.ts';

/** Link conditions of a MemoryNetwork. */
export interface MemoryNetworkOptions {
  /** One-way delay (ms) in each direction. Default 0 (delivered on the clock's next timer run). */
  latencyMs?: number;
  /** Extra one-way delay drawn uniformly from [0, jitterMs) per message; order is kept. Default 0. */
  jitterMs?: number;
  /** Random source in [0, 1) for jitter (seed it in tests). Default: a fixed-seed LCG. */
  random?: () => number;
}

/** The server's side of one connection. */
export interface MemoryPeer {
  /** A label (connection number and URL) for logs. */
  readonly label: string;
  send(data: Uint8Array): void;
  /** Closes cleanly with a code and reason; both ends see it after the latency. */
  close(code?: number, reason?: string): void;
  /** Messages from the client, in order. */
  onMessage(fn: (data: Uint8Array) => void): void;
  /** Called once when the link closes (either side). */
  onClose(fn: (code: number, reason: string) => void): void;
  isOpen(): boolean;
  /** Bytes sent by the server and not yet delivered to the client. */
  bufferedAmount(): number;
}

interface Direction {
  lastDueMs: number;
  inFlightBytes: number;
}

/** A set of listening URLs and the links between clients and them. */
export class MemoryNetwork {
  readonly clock: Clock;
  private readonly latency: number;
  private readonly jitter: number;
  private readonly random: () => number;
  private readonly listeners = new Map<string, (peer: MemoryPeer) => void>();
  private readonly liveDrops = new Set<() => void>();
  private connections = 0;

  constructor(clock: Clock, opts: MemoryNetworkOptions = {}) {
    this.clock = clock;
    this.latency = opts.latencyMs ?? 0;
    this.jitter = opts.jitterMs ?? 0;
    if (!(this.latency >= 0) || !(this.jitter >= 0)) throw new Error('MemoryNetwork: latencyMs and jitterMs must be ≥ 0');
    let seed = 12345;
    this.random =
      opts.random ??
      (() => {
        seed = (seed * 1103515245 + 12345) >>> 0;
        return seed / 4294967296;
      });
  }

  /** Accepts connections to `url`; onConnect gets each new peer. Replaces an earlier listener. */
  listen(url: string, onConnect: (peer: MemoryPeer) => void): void {
    this.listeners.set(url, onConnect);
  }

  /** Stops accepting connections to `url` (existing links stay up); new connects are refused with 1006. */
  unlisten(url: string): void {
    this.listeners.delete(url);
  }

  /** Cuts every live link abruptly: both ends see code 1006, as after a network failure or a server crash. */
  dropAll(): void {
    for (const drop of [...this.liveDrops]) drop();
  }

  /** Number of connections ever attempted. */
  get connectionCount(): number {
    return this.connections;
  }

  private dueAt(dir: Direction): number {
    const now = this.clock.nowMs();
    const due = Math.max(now + this.latency + (this.jitter > 0 ? this.random() * this.jitter : 0), dir.lastDueMs);
    dir.lastDueMs = due;
    return due - now;
  }

  /** The TransportFactory clients use to reach this network's listeners. */
  readonly transport: TransportFactory = (url: string, handlers: TransportHandlers): Transport => {
    const n = ++this.connections;
    const clock = this.clock;
    const listener = this.listeners.get(url);
    let open = listener !== undefined;
    let closeNotified = false;
    // An abrupt drop loses what is in flight; a clean close delivers it first, as TCP would.
    let dropped = false;
    const toServer: Direction = { lastDueMs: 0, inFlightBytes: 0 };
    const toClient: Direction = { lastDueMs: 0, inFlightBytes: 0 };
    let serverMessage: ((d: Uint8Array) => void) | null = null;
    let serverClose: ((code: number, reason: string) => void) | null = null;
    const early: Uint8Array[] = [];

    const notifyClose = (code: number, reason: string, delayMs: number): void => {
      if (closeNotified) return;
      closeNotified = true;
      open = false;
      this.liveDrops.delete(drop);
      const now = clock.nowMs();
      const afterInFlight = dropped ? 0 : Math.max(toServer.lastDueMs, toClient.lastDueMs) - now;
      clock.setTimer(Math.max(delayMs, afterInFlight), () => {
        serverClose?.(code, reason);
        handlers.close(code, reason);
      });
    };
    const drop = (): void => {
      dropped = true;
      notifyClose(1006, 'connection lost', 0);
    };

    if (listener === undefined) {
      notifyClose(1006, `connection to ${url} refused`, this.latency);
      return { send: () => undefined, close: () => undefined, bufferedAmount: () => 0 };
    }
    this.liveDrops.add(drop);

    const peer: MemoryPeer = {
      label: `memory#${n} ${url}`,
      send: (data) => {
        if (!open) return;
        const copy = data.slice();
        toClient.inFlightBytes += copy.length;
        clock.setTimer(this.dueAt(toClient), () => {
          toClient.inFlightBytes -= copy.length;
          if (!dropped) handlers.message(copy);
        });
      },
      close: (code = 1000, reason = '') => {
        if (open) notifyClose(code, reason, this.latency);
      },
      onMessage: (fn) => {
        serverMessage = fn;
        for (const d of early.splice(0)) fn(d);
      },
      onClose: (fn) => {
        serverClose = fn;
      },
      isOpen: () => open,
      bufferedAmount: () => toClient.inFlightBytes,
    };

    // The handshake takes one latency; the server sees the peer first, then the client its open event.
    clock.setTimer(this.latency, () => {
      if (closeNotified) return;
      listener(peer);
      if (!closeNotified) handlers.open();
    });

    return {
      send: (data: Uint8Array) => {
        if (!open) return;
        const copy = data.slice();
        toServer.inFlightBytes += copy.length;
        clock.setTimer(this.dueAt(toServer), () => {
          toServer.inFlightBytes -= copy.length;
          if (dropped) return;
          if (serverMessage) serverMessage(copy);
          else early.push(copy);
        });
      },
      close: (code = 1000, reason = '') => {
        if (open) notifyClose(code, reason, this.latency);
      },
      bufferedAmount: () => toServer.inFlightBytes,
    };
  };
}
