// The default transport: the platform's global WebSocket (browsers, Node 24). Binary frames only; a text frame or a
// connection error ends the link through the close handler with a readable reason.
import type { Transport, TransportFactory, TransportHandlers } from './transport.ts';

/** Close code for a link that failed abnormally (no close frame), as browsers report it. */
export const ABNORMAL_CLOSE = 1006;

/** Longest close reason a WebSocket accepts (bytes of UTF-8). */
const MAX_CLOSE_REASON_BYTES = 123;

/**
 * A close code the platform WebSocket lets a client send: browsers and Node's global WebSocket throw on anything but
 * 1000 and 3000–4999, so protocol-level codes (1001–1999) travel as 4000 + (code − 1000), e.g. 1002 as 4002.
 */
export function sendableCloseCode(code: number): number {
  if (code === 1000 || (code >= 3000 && code <= 4999)) return code;
  if (code > 1000 && code < 2000) return 4000 + (code - 1000);
  return 1000;
}

// A close reason cut to what the WebSocket accepts, on a character boundary.
function sendableReason(reason: string): string {
  const encoder = new TextEncoder();
  let out = reason;
  while (encoder.encode(out).length > MAX_CLOSE_REASON_BYTES) out = out.slice(0, -1);
  return out;
}

/** Opens a WebSocket transport; throws only when this runtime has no global WebSocket. */
export const webSocketTransport: TransportFactory = (url: string, handlers: TransportHandlers): Transport => {
  const WS = (globalThis as { WebSocket?: typeof WebSocket }).WebSocket;
  if (WS === undefined) throw new Error('webSocketTransport: this runtime has no global WebSocket (use Node 24+ or a browser, or pass a transport)');
  let closed = false;
  const finish = (code: number, reason: string): void => {
    if (closed) return;
    closed = true;
    handlers.close(code, reason);
  };
  let socket: WebSocket;
  try {
    socket = new WS(url);
  } catch (e) {
    // A malformed URL throws synchronously: report it like any failed connection, on a later turn.
    const message = e instanceof Error ? e.message : String(e);
    queueMicrotask(() => finish(ABNORMAL_CLOSE, `cannot open ${url}: ${message}`));
    return { send: () => undefined, close: () => undefined, bufferedAmount: () => 0 };
  }
  socket.binaryType = 'arraybuffer';
  socket.onopen = () => handlers.open();
  socket.onmessage = (ev: MessageEvent) => {
    if (closed) return;
    if (ev.data instanceof ArrayBuffer) handlers.message(new Uint8Array(ev.data));
    else {
      socket.close(sendableCloseCode(1003), 'text frames are not part of the protocol');
      finish(1003, 'server sent a text frame');
    }
  };
  socket.onerror = () => {
    // The close event follows with the details; nothing to add here.
  };
  socket.onclose = (ev: CloseEvent) => finish(ev.code || ABNORMAL_CLOSE, ev.reason || (ev.wasClean ? 'closed' : `connection to ${url} failed or dropped`));
  return {
    send(data: Uint8Array) {
      if (closed || socket.readyState !== 1) return;
      socket.send(data);
    },
    close(code = 1000, reason = '') {
      if (socket.readyState === 0 || socket.readyState === 1) socket.close(sendableCloseCode(code), sendableReason(reason));
    },
    bufferedAmount: () => socket.bufferedAmount,
  };
};
