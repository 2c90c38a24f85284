// An in-process client⇄server link on a Clock: each direction delivers whole messages after a latency (timers, never
// re-entrantly), counts queued bytes as bufferedAmount, and can be stalled to model a reader that stopped reading.
// Used by the test harness and the in-process benchmark; the server sees it as an ordinary ServerConnection.
import type { Clock } from '../shared/clock.ts';
import { clampCloseReason, type ConnectionHandlers, type ServerConnection } from './connection.ts';

/** Options of createMemoryLink. */
export interface MemoryLinkOptions {
  clock: Clock;
  /** One-way delay in ms (both directions). Default 0: delivered on the clock's next timer run. */
  latencyMs?: number;
  /** Label the server logs for this peer. */
  remote?: string;
  /** Largest client→server message; bigger ones close the link with 1009 as ws would. Default: unlimited. */
  maxPayloadBytes?: number;
}

/** The client end of a memory link. */
export interface MemoryClientEnd {
  send(data: Uint8Array): void;
  /** Sends a text frame (which the protocol refuses). */
  sendText(text: string): void;
  onMessage(fn: (data: Uint8Array) => void): void;
  onClose(fn: (code: number, reason: string) => void): void;
  close(code?: number, reason?: string): void;
  isOpen(): boolean;
  /** While stalled, server→client messages pile up (and count in the server's bufferedAmount). */
  setStalled(stalled: boolean): void;
}

/** A connected pair. */
export interface MemoryLink {
  server: ServerConnection;
  client: MemoryClientEnd;
}

/** Creates a connected client/server pair. */
export function createMemoryLink(opts: MemoryLinkOptions): MemoryLink {
  const clock = opts.clock;
  const latency = opts.latencyMs ?? 0;
  let open = true;
  let stalled = false;
  let serverHandlers: ConnectionHandlers | null = null;
  const earlyToServer: Array<[Uint8Array, boolean]> = [];
  let clientMessage: ((d: Uint8Array) => void) | null = null;
  let clientClose: ((code: number, reason: string) => void) | null = null;
  const toClient: Uint8Array[] = [];
  let toClientBytes = 0;
  let closeNotified = false;

  const flushToClient = (): void => {
    while (!stalled && toClient.length > 0) {
      const msg = toClient.shift()!;
      toClientBytes -= msg.length;
      clientMessage?.(msg);
    }
  };

  const notifyClose = (code: number, reason: string): void => {
    if (closeNotified) return;
    closeNotified = true;
    clock.setTimer(latency, () => {
      serverHandlers?.close(code, reason);
      clientClose?.(code, reason);
    });
  };

  const deliverToServer = (data: Uint8Array, binary: boolean): void => {
    if (!open) return;
    if (opts.maxPayloadBytes !== undefined && data.length > opts.maxPayloadBytes) {
      open = false;
      notifyClose(1009, 'Max payload size exceeded');
      return;
    }
    const copy = data.slice();
    clock.setTimer(latency, () => {
      if (!open && !closeNotified) return;
      if (serverHandlers) serverHandlers.message(copy, binary);
      else earlyToServer.push([copy, binary]);
    });
  };

  const server: ServerConnection = {
    remote: opts.remote ?? 'memory',
    send(data) {
      if (!open) return;
      const copy = data.slice();
      toClientBytes += copy.length;
      clock.setTimer(latency, () => {
        toClient.push(copy);
        flushToClient();
      });
    },
    bufferedAmount: () => toClientBytes,
    isOpen: () => open,
    close(code, reason) {
      if (!open) return;
      open = false;
      notifyClose(code, clampCloseReason(reason));
    },
    attach(handlers) {
      serverHandlers = handlers;
      for (const [d, b] of earlyToServer.splice(0)) handlers.message(d, b);
    },
  };

  const client: MemoryClientEnd = {
    send: (data) => deliverToServer(data, true),
    sendText: (text) => deliverToServer(new TextEncoder().encode(text), false),
    onMessage(fn) {
      clientMessage = fn;
    },
    onClose(fn) {
      clientClose = fn;
    },
    close(code = 1000, reason = '') {
      if (!open) return;
      open = false;
      notifyClose(code, reason);
    },
    isOpen: () => open,
    setStalled(s) {
      stalled = s;
      if (!s) flushToClient();
    },
  };
  return { server, client };
}
