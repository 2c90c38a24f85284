// A bare-TCP WebSocket client for hostile-client tests: it does the upgrade by hand, can bind a local loopback address,
// writes masked frames as fast as asked, and — unlike a real client — never answers a close frame or a ping.
import { randomBytes } from 'node:crypto';
import { connect, type Socket } from 'node:net';

/** A raw socket after its upgrade attempt: the HTTP status line's code and the response head. */
export interface RawWs {
  socket: Socket;
  status: number;
  head: string;
  /** Bytes received after the response head (frames). */
  received: number;
  closed: boolean;
}

/** Opens a TCP connection to ws://host:port/ from `localAddress` and sends the upgrade request; resolves on the answer. */
export function openRawWs(url: string, opts: { localAddress?: string; timeoutMs?: number } = {}): Promise<RawWs> {
  const u = new URL(url);
  return new Promise((resolve, reject) => {
    const socket = connect({ host: u.hostname, port: Number(u.port), localAddress: opts.localAddress });
    const ws: RawWs = { socket, status: 0, head: '', received: 0, closed: false };
    let buffered = Buffer.alloc(0);
    const timer = setTimeout(() => {
      socket.destroy();
      reject(new Error(`no upgrade answer from ${url} within ${opts.timeoutMs ?? 5000} ms`));
    }, opts.timeoutMs ?? 5000);
    socket.on('error', (e) => {
      clearTimeout(timer);
      if (ws.status === 0) reject(e);
    });
    socket.on('close', () => {
      ws.closed = true;
      clearTimeout(timer);
      if (ws.status === 0) reject(new Error('closed before an upgrade answer'));
    });
    socket.on('connect', () => {
      const key = randomBytes(16).toString('base64');
      socket.write(`GET ${u.pathname} HTTP/1.1\r\nHost: ${u.host}\r\nUpgrade: websocket\r\nConnection: Upgrade\r\nSec-WebSocket-Key: ${key}\r\nSec-WebSocket-Version: 13\r\n\r\n`);
    });
    socket.on('data', (chunk: Buffer) => {
      if (ws.status !== 0) {
        ws.received += chunk.length;
        return;
      }
      buffered = Buffer.concat([buffered, chunk]);
      const end = buffered.indexOf('\r\n\r\n');
      if (end < 0) return;
      ws.head = buffered.subarray(0, end).toString('latin1');
      ws.status = Number(/^HTTP\/1\.1 (\d{3})/.exec(ws.head)?.[1] ?? 0);
      ws.received = buffered.length - end - 4;
      clearTimeout(timer);
      resolve(ws);
    });
  });
}

/** One masked binary frame (mask key 0, allowed by RFC 6455) carrying `payload` (< 64 KiB). */
export function maskedFrame(payload: Uint8Array): Buffer {
  const n = payload.length;
  const head = n < 126 ? Buffer.from([0x82, 0x80 | n]) : Buffer.from([0x82, 0x80 | 126, n >> 8, n & 255]);
  return Buffer.concat([head, Buffer.alloc(4), payload]);
}
