// The server's view of one client link, independent of the transport: send bytes, see how much is queued, close
// with a reason, and receive messages/close notices. The ws gateway and the in-memory test link both implement it.

/** WebSocket close codes the server uses. */
export const CloseCode = {
  Normal: 1000,
  GoingAway: 1001,
  ProtocolError: 1002,
  UnsupportedData: 1003,
  PolicyViolation: 1008,
  /** Never sent: what a link reports when it died without a close frame (network loss, a missed heartbeat). */
  Abnormal: 1006,
  MessageTooBig: 1009,
  InternalError: 1011,
  TryAgainLater: 1013,
} as const;
export type CloseCode = (typeof CloseCode)[keyof typeof CloseCode];

/** Callbacks a connection delivers to its owner (the client session). */
export interface ConnectionHandlers {
  /** One whole message. `binary` is false for a text frame (which the protocol never uses). */
  message(data: Uint8Array, binary: boolean): void;
  /** The link closed (by either side); called once. */
  close(code: number, reason: string): void;
}

/** One client link as the server sees it. */
export interface ServerConnection {
  /** A short description of the peer for logs (address:port, or a test label). */
  readonly remote: string;
  /** Queues one binary message; a no-op once closed. */
  send(data: Uint8Array): void;
  /** Bytes queued but not yet written to the network. */
  bufferedAmount(): number;
  /** Whether the link is still open for sending. */
  isOpen(): boolean;
  /** Closes the link with a code and a human-readable reason (≤ 123 bytes of UTF-8). */
  close(code: number, reason: string): void;
  /** Installs the owner's callbacks; messages that arrived before are delivered then, in order. */
  attach(handlers: ConnectionHandlers): void;
  /** The client said a valid hello (a transport's connection policy stops counting it as half-open). */
  helloed?(): void;
  /** The server is disconnecting the client for misbehaving: the transport may stop reading it and penalize its address. */
  kicked?(reason: string): void;
}

/** Cuts a close reason to the 123 bytes a WebSocket close frame allows, on a character boundary. */
export function clampCloseReason(reason: string): string {
  const enc = new TextEncoder();
  if (enc.encode(reason).length <= 123) return reason;
  let out = '';
  for (const ch of reason) {
    if (enc.encode(out + ch).length > 120) break;
    out += ch;
  }
  return `${out}…`;
}
