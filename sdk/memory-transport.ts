// An in-memory network on a Clock for tests and tools: servers listen on URLs, clients connect through an ordinary
// TransportFactory; each direction delivers whole messages in order after latency plus seeded jitter (a TCP-like
// link conditioner). Peers can be dropped abruptly and URLs taken down to test reconnects; a client can stall its
// reading (the server sees its bytes pile up), send a text frame, or be cut off for an oversize message as by ws.
// The one in-memory link of the project: the SDK's tests, the server's test harness and the bots all use it.
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
  /** Largest client→server message; a bigger one closes the link with 1009 as ws would. Default: unlimited. */
  maxPayloadBytes?: number;
  /**
   * Share of messages whose first transmission is lost, in [0, 1): as on TCP the message still arrives in order, one
   * retransmission timeout later (and holds back those behind it). Default 0.
   */
  lossRate?: number;
  /** Extra delay of a lost message (ms). Default: max(200, 2 × round trip), TCP's minimum retransmission timeout. */
  retransmitMs?: number;
}

/** A client's end of a MemoryNetwork link: an ordinary Transport plus what protocol-level tests need. */
export interface MemoryTransport extends Transport {
  /** Sends a text frame (the protocol uses binary frames only; servers refuse text). */
  sendText(text: string): void;
  /** While stalled, arriving messages wait unread and still count in the server's bufferedAmount. */
  setStalled(stalled: boolean): void;
}

/** The server's side of one connection. */
export interface MemoryPeer {
  /** A label (connection number and URL) for logs. */
  readonly label: string;
  send(data: Uint8Array): void;
  /** Closes cleanly with a code and reason; both ends see it after the latency. */
  close(code?: number, reason?: string): void;
  /** Messages from the client, in order; `binary` is false for a text frame. */
  onMessage(fn: (data: Uint8Array, binary: boolean) => void): void;
  /** Called once when the link closes (either side). */
  onClose(fn: (code: number, reason: string) => void): void;
  isOpen(): boolean;
  /** Bytes sent by the server and not yet read by the client (in flight, or waiting while the client stalls). */
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
  private readonly lossRate: number;
  private readonly retransmitMs: number;
  private readonly random: () => number;
  private readonly maxPayloadBytes: number;
  private readonly listeners = new Map<string, (peer: MemoryPeer) => void>();
  private readonly liveDrops = new Set<() => void>();
  private connections = 0;

  constructor(clock: Clock, opts: MemoryNetworkOptions = {}) {
    this.clock = clock;
    this.latency = opts.latencyMs ?? 0;
    this.jitter = opts.jitterMs ?? 0;
    this.lossRate = opts.lossRate ?? 0;
    if (!(this.lossRate >= 0 && this.lossRate < 1)) throw new Error('MemoryNetwork: lossRate must be in [0, 1)');
    this.retransmitMs = opts.retransmitMs ?? Math.max(200, 4 * (this.latency + this.jitter));
    this.maxPayloadBytes = opts.maxPayloadBytes ?? Number.POSITIVE_INFINITY;
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
    const lost = this.lossRate > 0 && this.random() < this.lossRate ? this.retransmitMs : 0;
    const due = Math.max(now + this.latency + lost + (this.jitter > 0 ? this.random() * this.jitter : 0), dir.lastDueMs);
    dir.lastDueMs = due;
    return due - now;
  }

  /** The TransportFactory clients use to reach this network's listeners. */
  readonly transport: TransportFactory = (url: string, handlers: TransportHandlers): Transport => this.connect(url, handlers);

  /** Opens a link to `url` (what `transport` does); `label` names the peer for the server's logs. */
  connect(url: string, handlers: TransportHandlers, label?: string): MemoryTransport {
    const n = ++this.connections;
    const clock = this.clock;
    const listener = this.listeners.get(url);
    let open = listener !== undefined;
    let closeNotified = false;
    // An abrupt drop loses what is in flight; a clean close delivers it first, as TCP would.
    let dropped = false;
    const toServer: Direction = { lastDueMs: 0, inFlightBytes: 0 };
    const toClient: Direction = { lastDueMs: 0, inFlightBytes: 0 };
    let serverMessage: ((d: Uint8Array, binary: boolean) => void) | null = null;
    let serverClose: ((code: number, reason: string) => void) | null = null;
    const early: Array<[Uint8Array, boolean]> = [];
    let stalled = false;
    const unread: Uint8Array[] = [];
    // Messages that reached the client; read in order unless it stalls. An abrupt drop loses them.
    const readUnread = (): void => {
      while (unread.length > 0 && (dropped || !stalled)) {
        const data = unread.shift()!;
        toClient.inFlightBytes -= data.length;
        if (!dropped) handlers.message(data);
      }
    };

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
      readUnread();
      notifyClose(1006, 'connection lost', 0);
    };

    if (listener === undefined) {
      notifyClose(1006, `connection to ${url} refused`, this.latency);
      return { send: () => undefined, sendText: () => undefined, close: () => undefined, bufferedAmount: () => 0, setStalled: () => undefined };
    }
    this.liveDrops.add(drop);

    const peer: MemoryPeer = {
      label: label ?? `memory#${n} ${url}`,
      send: (data) => {
        if (!open) return;
        const copy = data.slice();
        toClient.inFlightBytes += copy.length;
        clock.setTimer(this.dueAt(toClient), () => {
          unread.push(copy);
          readUnread();
        });
      },
      close: (code = 1000, reason = '') => {
        if (open) notifyClose(code, reason, this.latency);
      },
      onMessage: (fn) => {
        serverMessage = fn;
        for (const [d, binary] of early.splice(0)) fn(d, binary);
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

    const sendToServer = (data: Uint8Array, binary: boolean): void => {
      if (!open) return;
      if (data.length > this.maxPayloadBytes) {
        notifyClose(1009, 'Max payload size exceeded', this.latency);
        return;
      }
      const copy = data.slice();
      toServer.inFlightBytes += copy.length;
      clock.setTimer(this.dueAt(toServer), () => {
        toServer.inFlightBytes -= copy.length;
        if (dropped) return;
        if (serverMessage) serverMessage(copy, binary);
        else early.push([copy, binary]);
      });
    };

    return {
      send: (data) => sendToServer(data, true),
      sendText: (text) => sendToServer(new TextEncoder().encode(text), false),
      close: (code = 1000, reason = '') => {
        if (open) notifyClose(code, reason, this.latency);
      },
      bufferedAmount: () => toServer.inFlightBytes,
      setStalled: (s) => {
        stalled = s;
        readUnread();
      },
    };
  }
}
