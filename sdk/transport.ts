// The transport seam of the client library: a message-oriented, reliable, ordered link (a WebSocket in the browser
// and Node 24; an in-memory link in tests). The client never touches a socket directly.

/** Callbacks a transport delivers, each on its own turn (never from inside send() or close()). */
export interface TransportHandlers {
  /** The link is up; sending is possible. */
  open(): void;
  /** One whole binary message. */
  message(data: Uint8Array): void;
  /** The link is gone (closed by either side, or never opened: code 1006); called exactly once. */
  close(code: number, reason: string): void;
}

/** One live link. */
export interface Transport {
  /** Queues one binary message; ignored once closed. */
  send(data: Uint8Array): void;
  /** Closes the link (the close handler still runs once). */
  close(code?: number, reason?: string): void;
  /** Bytes queued locally and not yet sent. */
  bufferedAmount(): number;
}

/** Opens a link to a URL; failures arrive as handlers.close (never as exceptions from here). */
export type TransportFactory = (url: string, handlers: TransportHandlers) => Transport;
