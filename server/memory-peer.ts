// Adapts the client library's in-memory network peer (sdk/memory-transport.ts, described structurally here so
// server/ never imports client code) to a ServerConnection: in-process tests and tools serve MemoryNetwork clients.
import { clampCloseReason, type ConnectionHandlers, type ServerConnection } from './connection.ts';

/** The server side of a MemoryNetwork link (the shape of sdk's MemoryPeer). */
export interface MemoryPeerLike {
  readonly label: string;
  send(data: Uint8Array): void;
  close(code?: number, reason?: string): void;
  onMessage(fn: (data: Uint8Array, binary: boolean) => void): void;
  onClose(fn: (code: number, reason: string) => void): void;
  isOpen(): boolean;
  bufferedAmount(): number;
}

/** Wraps a MemoryNetwork peer as a ServerConnection (closes are reported once). */
export function memoryPeerConnection(peer: MemoryPeerLike): ServerConnection {
  return {
    remote: peer.label,
    send: (data) => peer.send(data),
    bufferedAmount: () => peer.bufferedAmount(),
    isOpen: () => peer.isOpen(),
    close: (code, reason) => peer.close(code, clampCloseReason(reason)),
    attach(handlers: ConnectionHandlers) {
      let closed = false;
      peer.onMessage((data, binary) => handlers.message(data, binary));
      peer.onClose((code, reason) => {
        if (closed) return;
        closed = true;
        handlers.close(code, reason);
      });
    },
  };
}
