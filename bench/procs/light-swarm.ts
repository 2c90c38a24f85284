// A light bot swarm: N players that send the server exactly what the client library sends — hello, pings (5 quick,
// then one a second) feeding the library's ClockSync, input messages from its InputSender (newest command plus 3
// repeats) aimed by its InputLead on the library's half-tick pump, an ack per snapshot — but only read each
// snapshot's header instead of decoding it, so one core of bots can load a server core. Prints {"ready"}, {"window"}
// after SETTLE_MS, {"report"} after WINDOW_MS, and plays on until stopped.
// Run: node bench/procs/light-swarm.ts WS_URL CLIENTS SETTLE_MS WINDOW_MS [ROOMS]
// (ROOMS 0: everyone in the default room; R > 0: client i joins room r((i mod R) + 1)).
import WebSocket from 'ws';
import { decodeServerMessage, DEFAULT_INPUT_REDUNDANCY, encodeClientMessage, PROTOCOL_VERSION, readSnapshotHeader, type ClientMessage } from '../../shared/protocol/index.ts';
import { BotScript } from '../../shared/sim/bots.ts';
import { ClockSync, InputLead, InputSender } from '../lib/client-lib.ts';
import { TICK_MS } from '../../shared/tick-rate.ts';

const [url, nArg, settleArg, windowArg, roomsArg] = process.argv.slice(2);
const n = Number(nArg);
const settleMs = Number(settleArg);
const windowMs = Number(windowArg);
const rooms = Number(roomsArg ?? 0);
if (!url || !Number.isInteger(n) || n < 1 || !(settleMs >= 0) || !(windowMs > 0) || !Number.isInteger(rooms) || rooms < 0) {
  process.stderr.write('usage: node bench/procs/light-swarm.ts WS_URL CLIENTS SETTLE_MS WINDOW_MS [ROOMS]\n');
  process.exit(2);
}
const say = (obj: unknown): void => void process.stdout.write(`${JSON.stringify(obj)}\n`);
/** The client library's defaults (sdk//client.ts and link-session.ts). */
const INITIAL_PINGS = 5;
const INITIAL_PING_SPACING_MS = 100;
const PING_INTERVAL_MS = 1000;
const PUMP_SPACING_TICKS = 0.5;

interface LightBot {
  ws: WebSocket;
  sync: ClockSync | null;
  lead: InputLead | null;
  sender: InputSender;
  missedInputTicks: number | null;
  pingsSent: number;
  nextPingMs: number;
  closed: boolean;
  /** The newest snapshot tick received (completes the next delta snapshot's tick). */
  snapshotTick: number | null;
}

const sent = { input: 0, ack: 0, ping: 0, bytes: 0 };
const received = { snapshots: 0, bytes: 0, messages: 0 };
let protocolErrors = 0;

function send(b: LightBot, m: ClientMessage): void {
  if (b.ws.readyState !== WebSocket.OPEN) return;
  const bytes = encodeClientMessage(m);
  sent.bytes += bytes.length;
  b.ws.send(bytes);
}

function ping(b: LightBot, nowMs: number): void {
  send(b, { type: 'ping', clientTimeMs: nowMs });
  sent.ping++;
  b.pingsSent++;
  b.nextPingMs = nowMs + (b.pingsSent < INITIAL_PINGS ? INITIAL_PING_SPACING_MS : PING_INTERVAL_MS);
}

function onMessage(b: LightBot, data: Buffer): void {
  const now = performance.now();
  received.messages++;
  received.bytes += data.byteLength;
  const r = decodeServerMessage(new Uint8Array(data.buffer, data.byteOffset, data.byteLength));
  if (!r.ok) {
    protocolErrors++;
    return;
  }
  const m = r.message;
  if (m.type === 'snapshot') {
    received.snapshots++;
    b.snapshotTick = readSnapshotHeader(m.bytes, b.snapshotTick).tick;
    send(b, { type: 'ack', tick: b.snapshotTick });
    sent.ack++;
  } else if (m.type === 'pong' && b.sync) {
    b.sync.addSample({ sentLocalMs: m.clientTimeMs, receivedLocalMs: now, serverTick: m.serverTick, serverTimeMs: m.serverTimeMs });
    b.missedInputTicks = m.missedInputTicks;
  } else if (m.type === 'welcome') {
    b.sync = new ClockSync({ tickRateHz: m.tickRateHz });
    b.sync.seed(m.tick, now);
    b.lead = new InputLead({ tickRateHz: m.tickRateHz });
    ping(b, now);
  } else if (m.type === 'error' || m.type === 'bye') protocolErrors++;
}

function connectBot(i: number): Promise<LightBot> {
  const ws = new WebSocket(url, { perMessageDeflate: false });
  const bot: LightBot = { ws, sync: null, lead: null, sender: new InputSender({ redundancy: DEFAULT_INPUT_REDUNDANCY }), missedInputTicks: null, pingsSent: 0, nextPingMs: 0, closed: false, snapshotTick: null };
  return new Promise((resolve, reject) => {
    ws.on('open', () => send(bot, { type: 'hello', version: PROTOCOL_VERSION, name: `light-${i + 1}`, room: rooms > 0 ? `r${(i % rooms) + 1}` : null }));
    ws.on('message', (data: Buffer) => {
      onMessage(bot, data);
      if (bot.sync) resolve(bot);
    });
    ws.on('close', () => {
      bot.closed = true;
      reject(new Error(`light bot ${i + 1} closed before its welcome`));
    });
    ws.on('error', (e) => reject(e));
  });
}

/** LinkSession.pump for every bot: target = estimated server tick at arrival + lead beyond the half-tick pump spacing. */
function pump(bots: readonly LightBot[]): void {
  const now = performance.now();
  for (const b of bots) {
    if (!b.sync || !b.lead || b.closed) continue;
    if (now >= b.nextPingMs) ping(b, now);
    b.lead.update(b.sync.jitterMs, b.missedInputTicks, now);
    const oneWayMs = (b.sync.rttMs ?? 0) / 2;
    const target = Math.floor(b.sync.serverTickAt(now + oneWayMs) + Math.max(0, b.lead.leadTicks - PUMP_SPACING_TICKS));
    if (target < 0) continue;
    const msg = b.sender.update(target);
    if (msg !== null) {
      send(b, msg);
      sent.input++;
    }
  }
}

const bots: LightBot[] = [];
const CONNECT_BATCH = 16;
for (let i = 0; i < n; i += CONNECT_BATCH) {
  const batch: Promise<LightBot>[] = [];
  for (let j = i; j < Math.min(n, i + CONNECT_BATCH); j++) batch.push(connectBot(j));
  bots.push(...(await Promise.all(batch)));
}
say({ ready: bots.length });

const script = new BotScript({ seed: 7, bots: n, joinTicks: bots.map(() => 0), fire: false });
const steer = setInterval(() => {
  const record = script.next();
  for (let i = 0; i < record.commands.length; i++) bots[i].sender.setCommand(record.commands[i].input);
}, TICK_MS);
const pumper = setInterval(() => pump(bots), TICK_MS * PUMP_SPACING_TICKS);

await new Promise((r) => setTimeout(r, settleMs));
const start = { atMs: performance.now(), cpu: process.cpuUsage(), sent: { ...sent }, received: { ...received } };
say({ window: true });
await new Promise((r) => setTimeout(r, windowMs));
const seconds = (performance.now() - start.atMs) / 1000;
const cpu = process.cpuUsage(start.cpu);
const perClientPerSecond = (count: number): number => count / n / seconds;
say({
  report: {
    clients: n,
    seconds,
    snapshotsPerClientPerSecond: perClientPerSecond(received.snapshots - start.received.snapshots),
    inputMessagesPerClientPerSecond: perClientPerSecond(sent.input - start.sent.input),
    acksPerClientPerSecond: perClientPerSecond(sent.ack - start.sent.ack),
    pingsPerClientPerSecond: perClientPerSecond(sent.ping - start.sent.ping),
    kbpsUpPerClient: (perClientPerSecond(sent.bytes - start.sent.bytes) * 8) / 1000,
    kbpsPerClient: (perClientPerSecond(received.bytes - start.received.bytes) * 8) / 1000,
    failedSnapshots: 0,
    closedClients: bots.filter((b) => b.closed).length,
    protocolErrors,
    cpuShare: (cpu.user + cpu.system) / 1e6 / seconds,
  },
});
// Stay connected and sending while the server reports its side of the window (the figure then stops this process).
setTimeout(() => {
  clearInterval(steer);
  clearInterval(pumper);
  for (const b of bots) b.ws.close();
  setTimeout(() => process.exit(0), 500).unref();
}, 5000);
