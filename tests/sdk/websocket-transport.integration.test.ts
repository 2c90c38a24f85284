// Tests for sdk/websocket-transport.ts over a real loopback socket with Node's global WebSocket (which, like every
// browser, refuses to send close codes other than 1000 and 3000–4999): a client that must hang up on a server of
// another protocol version does hang up, with a code it is allowed to send, and says why.
import { afterEach, describe, expect, it } from 'vitest';
import { WebSocketServer } from 'ws';
import { connect, type NetClient } from '../../sdk/client.ts';
import { sendableCloseCode } from '../../sdk/websocket-transport.ts';
import { packValue } from '../../shared/protocol/codec.ts';
import { PROTOCOL_VERSION, ServerOpcode } from '../../shared/protocol/index.ts';

describe('sendableCloseCode', () => {
  it('keeps the codes a WebSocket client may send and moves protocol codes into the 4000s', () => {
    expect(sendableCloseCode(1000)).toBe(1000);
    expect(sendableCloseCode(3000)).toBe(3000);
    expect(sendableCloseCode(4999)).toBe(4999);
    expect(sendableCloseCode(1002)).toBe(4002);
    expect(sendableCloseCode(1003)).toBe(4003);
    expect(sendableCloseCode(1006)).toBe(4006);
    expect(sendableCloseCode(2500)).toBe(1000);
  });
});

describe('webSocketTransport', () => {
  let server: WebSocketServer | null = null;
  let client: NetClient | null = null;
  afterEach(async () => {
    client?.close();
    await new Promise<void>((resolve) => (server ? server.close(() => resolve()) : resolve()));
    server = null;
  });

  it('hangs up on a server that welcomes it with another protocol version, and says so', { timeout: 20_000 }, async () => {
    server = new WebSocketServer({ host: '127.0.0.1', port: 0 });
    await new Promise<void>((resolve) => server!.once('listening', () => resolve()));
    const closes: number[] = [];
    let connections = 0;
    server.on('connection', (ws) => {
      connections++;
      ws.on('close', (code) => closes.push(code));
      ws.once('message', () => ws.send(packValue([ServerOpcode.Welcome, { protocolVersion: PROTOCOL_VERSION + 1 }])));
    });
    const { port } = server.address() as { port: number };
    client = connect(`ws://127.0.0.1:${port}/`, { name: 'Ada', room: null });
    const closed = await new Promise<{ reason: string; detail: string }>((resolve, reject) => {
      const timer = setTimeout(() => reject(new Error(`client still ${client!.state} 10 s after the foreign welcome`)), 10_000);
      client!.on('closed', (info) => {
        clearTimeout(timer);
        resolve(info);
      });
    });
    expect(closed.reason).toBe('version-mismatch');
    expect(closed.detail).toMatch(new RegExp(`server speaks protocol ${PROTOCOL_VERSION + 1}`));
    // The server saw the client's close frame (a code the client may send), and no second connection.
    await expect.poll(() => closes, { timeout: 5000 }).toEqual([4002]);
    expect(connections).toBe(1);
  });
});
