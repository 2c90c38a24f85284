// Drives hostile clients at a real server for the fuzz test: lanes of short-lived WebSockets, each from its own
// loopback address (127.10.0.0/16 and up, so per-address limits see strangers, never the honest players on
// 127.0.0.1), each running a seeded script: garbage before hello, hostile frames after a welcome, duplicate hellos,
// floods, silent sockets, raw TCP junk. Counts every generated frame; keeps each socket's recent frames for reports.
import { connect as tcpConnect } from 'node:net';
import { setImmediate as yieldToLoop } from 'node:timers/promises';
import WebSocket from 'ws';
import { decodeClientMessage, decodeServerMessage, encodeClientMessage, PROTOCOL_VERSION, readSnapshotHeader, type ClientMessage } from '../../shared/protocol/index.ts';
import { quantizeInput } from '../../shared/sim/input.ts';
import { Prng } from '../../shared/sim/prng.ts';
import { frameHex, hostileFrame, type HostileFrame } from './hostile-frames.ts';

/** What to fuzz, how much, and how hard. */
export interface FuzzOptions {
  url: string;
  seed: number;
  /** Generated hostile frames to send in all. */
  frames: number;
  /** Sockets open at once. */
  lanes: number;
  /** Give up (and say so) after this long. */
  deadlineMs: number;
  /** Source addresses for the fuzzing sockets: false uses the default (for systems that route only 127.0.0.1). */
  spreadAddresses: boolean;
}

/** What one socket ended with that the test must not accept: an internal error or an internal-error kick. */
export interface FuzzIncident {
  socket: number;
  what: string;
  /** Hex of the frames the socket sent (the last 24), newest last: the culprit is among them. */
  recentFrames: string[];
}

/** Totals of a fuzz run. */
export interface FuzzStats {
  generatedFrames: number;
  /** Valid frames sent around the generated ones (hellos, pings of a flood, plain inputs). */
  fillerFrames: number;
  sockets: number;
  /** Sockets whose connection or upgrade failed. */
  socketsRefused: number;
  rawTcpConnections: number;
  byKind: Record<string, number>;
  byeReasons: Record<string, number>;
  errorCodes: Record<string, number>;
  incidents: FuzzIncident[];
  seconds: number;
  /** Whether the deadline ended the run before `frames` were sent. */
  timedOut: boolean;
  /** The generated frames sent, oldest first (the last FRAME_LOG_LIMIT), to find a culprit after a failure. */
  frameLog: HostileFrame[];
}

/** Frames kept for the post-mortem (about 15 MB at 100,000). */
const FRAME_LOG_LIMIT = 200_000;

const SCRIPTS = [
  ['garbage', 36],
  ['joined', 40],
  ['flood', 1],
  ['silent', 3],
  ['raw-tcp', 3],
  ['prehello-join', 17],
] as const;
type Script = (typeof SCRIPTS)[number][0];

const RECENT = 24;
const delay = (ms: number): Promise<void> => new Promise((r) => setTimeout(r, ms));

/** The loopback source address of fuzz socket n (never 127.0.0.1). */
export function fuzzAddress(n: number): string {
  return `127.${10 + (Math.floor(n / (253 * 256)) % 200)}.${Math.floor(n / 253) % 256}.${(n % 253) + 1}`;
}

function pickScript(rng: Prng): Script {
  let r = rng.next() * SCRIPTS.reduce((n, [, w]) => n + w, 0);
  for (const [name, w] of SCRIPTS) {
    r -= w;
    if (r < 0) return name;
  }
  return 'garbage';
}

/** One fuzzing socket: sends, decodes what comes back, remembers what it sent. */
class FuzzSocket {
  readonly ws: WebSocket;
  readonly n: number;
  readonly stats: FuzzStats;
  readonly recent: HostileFrame[] = [];
  welcomed = false;
  tick = 0;
  /** The newest snapshot tick received (completes the next delta snapshot's tick). */
  snapshotTick: number | null = null;
  closed = false;

  constructor(n: number, stats: FuzzStats, url: string, localAddress: string | undefined) {
    this.n = n;
    this.stats = stats;
    // An all-zero mask (valid: the server unmasks either way) spares this process a random mask per frame.
    this.ws = new WebSocket(url, { localAddress, perMessageDeflate: false, handshakeTimeout: 5000, generateMask: () => {} });
    this.ws.on('error', () => {});
    this.ws.on('close', () => (this.closed = true));
    this.ws.on('message', (data: Buffer) => this.receive(new Uint8Array(data.buffer, data.byteOffset, data.byteLength)));
  }

  opened(): Promise<boolean> {
    return new Promise((resolve) => {
      this.ws.once('open', () => resolve(true));
      this.ws.once('close', () => resolve(false));
    });
  }

  get open(): boolean {
    return this.ws.readyState === WebSocket.OPEN;
  }

  private receive(bytes: Uint8Array): void {
    const r = decodeServerMessage(bytes);
    if (!r.ok) return this.incident(`undecodable server message: ${r.error}`);
    const m = r.message;
    if (m.type === 'welcome') {
      this.welcomed = true;
      this.tick = m.tick;
    } else if (m.type === 'snapshot') {
      this.snapshotTick = readSnapshotHeader(m.bytes, this.snapshotTick).tick;
      this.tick = Math.max(this.tick, this.snapshotTick);
    } else if (m.type === 'pong') {
      this.tick = Math.max(this.tick, m.serverTick);
    } else if (m.type === 'error') {
      this.stats.errorCodes[m.code] = (this.stats.errorCodes[m.code] ?? 0) + 1;
      if (m.code === 'internal') this.incident(`error ${m.code}: ${m.message}`);
    } else if (m.type === 'bye') {
      this.stats.byeReasons[m.reason] = (this.stats.byeReasons[m.reason] ?? 0) + 1;
      if (m.reason === 'kicked') this.incident(`bye ${m.reason}: ${m.message}`);
    }
  }

  private incident(what: string): void {
    this.stats.incidents.push({ socket: this.n, what, recentFrames: this.recent.map(frameHex) });
  }

  private remember(frame: HostileFrame): void {
    this.recent.push(frame);
    if (this.recent.length > RECENT) this.recent.shift();
  }

  /** Sends one generated frame; false once the socket is closed. */
  hostile(rng: Prng, aimAtTick = true): boolean {
    if (!this.open) return false;
    const frame = hostileFrame(rng, aimAtTick ? this.tick : rng.int(0, 1000));
    this.remember(frame);
    this.ws.send(frame.data, { binary: typeof frame.data !== 'string' });
    this.stats.generatedFrames++;
    if (this.stats.frameLog.length < FRAME_LOG_LIMIT) this.stats.frameLog.push(frame);
    this.stats.byKind[frame.kind] = (this.stats.byKind[frame.kind] ?? 0) + 1;
    return true;
  }

  /** Sends one valid message (filler). */
  valid(m: ClientMessage): boolean {
    if (!this.open) return false;
    const data = encodeClientMessage(m);
    this.remember({ kind: 'edge-message', data });
    this.ws.send(data);
    this.stats.fillerFrames++;
    return true;
  }

  async until(pred: () => boolean, timeoutMs: number): Promise<void> {
    const end = performance.now() + timeoutMs;
    while (!pred() && !this.closed && performance.now() < end) await delay(5);
  }

  end(rng: Prng): void {
    const r = rng.int(0, 3);
    if (r === 0) this.valid({ type: 'bye' });
    if (r < 3) this.ws.close();
    else this.ws.terminate();
  }
}

function randomInput(rng: Prng): Parameters<typeof quantizeInput> {
  return [rng.range(-1.2, 1.2), rng.range(-1.2, 1.2), rng.range(-10, 10), rng.range(-2, 2), rng.int(0, 31)];
}

async function burst(s: FuzzSocket, rng: Prng, count: number, mixValid: boolean): Promise<void> {
  for (let i = 0; i < count; i++) {
    const r = rng.next();
    let sent: boolean;
    if (!mixValid || r < 0.7) sent = s.hostile(rng);
    else if (r < 0.85) sent = s.valid({ type: 'input', firstTick: s.tick + 2, commands: [quantizeInput(...randomInput(rng))] });
    else if (r < 0.95) sent = s.valid(rng.next() < 0.5 ? { type: 'ack', tick: s.tick } : { type: 'ping', clientTimeMs: performance.now() });
    else sent = s.valid({ type: 'hello', version: PROTOCOL_VERSION, name: 'again', room: null }); // a duplicate hello
    if (!sent) return;
    if (i % 8 === 7) await (mixValid ? delay(rng.int(1, 6)) : yieldToLoop());
  }
}

async function rawTcp(url: string, rng: Prng, localAddress: string | undefined): Promise<void> {
  const { hostname, port } = new URL(url);
  const junk = rng.next() < 0.5 ? Buffer.from(Array.from({ length: rng.int(1, 300) }, () => rng.int(0, 255))) : Buffer.from(`GET / HTTP/1.1\r\nHost: x\r\nUpgrade: websocket\r\nConnection: Upgrade\r\nSec-WebSocket-Version: ${rng.pick(['13', '8', 'x'])}\r\nSec-WebSocket-Key: ${rng.pick(['', 'dGhlIHNhbXBsZSBub25jZQ==', '%%%'])}\r\n\r\n\u0000\u00ff`);
  await new Promise<void>((resolve) => {
    const sock = tcpConnect({ host: hostname, port: Number(port), localAddress }, () => sock.end(junk));
    sock.on('error', () => resolve());
    sock.on('close', () => resolve());
    sock.resume();
    setTimeout(() => sock.destroy(), 500).unref();
  });
}

async function runSocket(opts: FuzzOptions, stats: FuzzStats, n: number): Promise<void> {
  const rng = new Prng((opts.seed ^ Math.imul(n, 0x9e3779b1)) >>> 0);
  const script = pickScript(rng);
  const localAddress = opts.spreadAddresses ? fuzzAddress(n) : undefined;
  if (script === 'raw-tcp') {
    stats.rawTcpConnections++;
    return rawTcp(opts.url, rng, localAddress);
  }
  const s = new FuzzSocket(n, stats, opts.url, localAddress);
  stats.sockets++;
  if (!(await s.opened())) {
    stats.socketsRefused++;
    return;
  }
  switch (script) {
    case 'garbage':
      await burst(s, rng, rng.int(5, 24), false);
      break;
    case 'silent':
      await delay(rng.int(5, 60));
      break;
    case 'flood':
      for (let i = 0; i < 1300 && s.valid({ type: 'ping', clientTimeMs: i }); i++) if (i % 64 === 63) await yieldToLoop();
      break;
    case 'prehello-join':
    case 'joined': {
      if (script === 'prehello-join') await burst(s, rng, rng.int(1, 4), false);
      s.valid({ type: 'hello', version: PROTOCOL_VERSION, name: `fz${n % 1000}`, room: rng.pick([null, null, null, 'default', 'character-course']) });
      await s.until(() => s.welcomed, 3000);
      if (s.welcomed) await burst(s, rng, rng.int(10, 80), true);
      break;
    }
  }
  await s.until(() => false, rng.int(0, 1) === 0 ? 30 : 150); // let the server answer (or kick) before leaving
  if (s.open) s.end(rng);
}

/** Runs the fuzz until `frames` generated frames were sent (or the deadline passed); resolves with the totals. */
export async function runFuzz(opts: FuzzOptions): Promise<FuzzStats> {
  const stats: FuzzStats = { generatedFrames: 0, fillerFrames: 0, sockets: 0, socketsRefused: 0, rawTcpConnections: 0, byKind: {}, byeReasons: {}, errorCodes: {}, incidents: [], seconds: 0, timedOut: false, frameLog: [] };
  const started = performance.now();
  let next = 0;
  const lane = async (): Promise<void> => {
    while (stats.generatedFrames < opts.frames) {
      if (performance.now() - started > opts.deadlineMs) {
        stats.timedOut = true;
        return;
      }
      await runSocket(opts, stats, next++);
    }
  };
  await Promise.all(Array.from({ length: opts.lanes }, lane));
  stats.seconds = (performance.now() - started) / 1000;
  return stats;
}

/**
 * After a failure the server could not attribute to a frame (an uncaught error, a dead process): the sent frames
 * that make the client-frame decoder throw in this process, as hex (at most `max`).
 */
export function framesThatThrow(frames: readonly HostileFrame[], max = 5): string[] {
  const out: string[] = [];
  for (const f of frames) {
    try {
      decodeClientMessage(f.data);
    } catch (error) {
      out.push(`${frameHex(f)} (${error instanceof Error ? error.message : 'threw'})`);
      if (out.length >= max) break;
    }
  }
  return out;
}

/** Whether this system lets a socket bind a loopback address other than 127.0.0.1 (Linux does; macOS does not). */
export function canBindLoopbackRange(port: number): Promise<boolean> {
  return new Promise((resolve) => {
    const sock = tcpConnect({ host: '127.0.0.1', port, localAddress: fuzzAddress(0) }, () => {
      sock.destroy();
      resolve(true);
    });
    sock.on('error', () => resolve(false));
  });
}
