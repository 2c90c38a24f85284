// A protocol-level WebSocket test client for integration tests (the `ws` package): decodes every server message,
// decodes and acks snapshots, and waits for conditions with a bounded timeout.
import WebSocket from 'ws';
import {
  decodeServerMessage,
  encodeClientMessage,
  PROTOCOL_VERSION,
  snapshotFormatFromSpec,
  SnapshotDecoder,
  type ClientMessage,
  type QuantizedFrame,
  type ServerMessage,
  type WelcomeMessage,
} from '../../shared/protocol/index.ts';

/** How a test client opens its socket. */
export interface WsConnectOptions {
  /** Local address to bind (any of 127.0.0.0/8 is this machine on Linux). */
  localAddress?: string;
  /** Certificate authorities to trust for wss:// (PEM). */
  ca?: string | Buffer;
}

/** A connected test client. */
export class WsTestClient {
  readonly ws: WebSocket;
  readonly messages: ServerMessage[] = [];
  readonly frames: QuantizedFrame[] = [];
  welcome: WelcomeMessage | null = null;
  closed: { code: number; reason: string } | null = null;
  private decoder: SnapshotDecoder | null = null;

  private constructor(ws: WebSocket) {
    this.ws = ws;
    ws.on('message', (data: Buffer) => {
      const r = decodeServerMessage(new Uint8Array(data.buffer, data.byteOffset, data.byteLength));
      if (!r.ok) throw new Error(`undecodable server message: ${r.error}`);
      const m = r.message;
      this.messages.push(m);
      if (m.type === 'welcome') {
        this.welcome = m;
        this.decoder = new SnapshotDecoder(snapshotFormatFromSpec(m.scenario.bounds, m.snapshotFormat));
      } else if (m.type === 'snapshot' && this.decoder) {
        const f = this.decoder.decode(m.bytes).frame;
        this.frames.push(f);
        this.send({ type: 'ack', tick: f.tick });
      }
    });
    ws.on('close', (code, reason) => (this.closed = { code, reason: reason.toString('utf8') }));
    ws.on('error', () => {});
  }

  /** Opens a socket to `url` (from `localAddress` when given, e.g. another loopback address). */
  static async connect(url: string, opts: WsConnectOptions = {}): Promise<WsTestClient> {
    const ws = new WebSocket(url, { localAddress: opts.localAddress, ca: opts.ca });
    const c = new WsTestClient(ws);
    await new Promise<void>((resolve, reject) => {
      ws.once('open', () => resolve());
      ws.once('error', reject);
    });
    return c;
  }

  /** Connects and joins; resolves with the welcomed client. */
  static async join(url: string, name: string, room: string | null = null, opts: WsConnectOptions & { timeoutMs?: number } = {}): Promise<WsTestClient> {
    const c = await WsTestClient.connect(url, opts);
    c.send({ type: 'hello', version: PROTOCOL_VERSION, name, room });
    try {
      await c.waitFor(() => c.welcome !== null || c.closed !== null, opts.timeoutMs ?? 5000, 'welcome');
    } catch (error) {
      c.ws.terminate();
      throw error;
    }
    if (!c.welcome) throw new Error(`no welcome for ${name}: closed ${JSON.stringify(c.closed)} after ${JSON.stringify(c.messages.slice(-2))}`);
    return c;
  }

  send(m: ClientMessage): void {
    if (this.ws.readyState === WebSocket.OPEN) this.ws.send(encodeClientMessage(m));
  }

  sendRaw(bytes: Uint8Array): void {
    this.ws.send(bytes);
  }

  ofType<T extends ServerMessage['type']>(type: T): Extract<ServerMessage, { type: T }>[] {
    return this.messages.filter((m): m is Extract<ServerMessage, { type: T }> => m.type === type);
  }

  /** Resolves when `pred()` holds; rejects after `timeoutMs`. */
  async waitFor(pred: () => boolean, timeoutMs: number, what: string): Promise<void> {
    const start = performance.now();
    while (!pred()) {
      if (performance.now() - start > timeoutMs) throw new Error(`timed out after ${timeoutMs} ms waiting for ${what}`);
      await new Promise((r) => setTimeout(r, 5));
    }
  }

  close(): void {
    this.ws.close();
  }
}
