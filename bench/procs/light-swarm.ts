// A light bot swarm: N players that send the server exactly what the client library sends — hello, pings (5 quick,
// then one a second) feeding the library's ClockSync, input messages from its InputSender (newest command plus 3
// repeats) aimed by its InputLead on the library's half-tick pump, snapshot acks on them (its AckCarrier) — but only
// read each snapshot's header instead of decoding it, so one core of bots can load a server core. Prints {"ready"},
// {"window"} once SETTLE_MS have passed and every bot has seen its room run SETTLE_MS worth of ticks (a slowed server
// settles in simulated time too: a new room's rain has landed; at most SETTLE_LIMIT_MS), {"report"} after WINDOW_MS
// (with each room's snapshot gaps as its bots saw them and the swarm's own event-loop delay, which shows whether the
// bots themselves were late), and plays on until stopped; SIGTERM closes every socket with a close frame first, so the
// server lets the players go instead of holding them for a reconnect.
// Run: node bench/procs/light-swarm.ts WS_URL CLIENTS SETTLE_MS WINDOW_MS [ROOMS]
// (ROOMS 0: everyone in the default room; R > 0: client i joins room r((i mod R) + 1)).
import { monitorEventLoopDelay } from 'node:perf_hooks';
import WebSocket from 'ws';
import { decodeServerMessage, DEFAULT_INPUT_REDUNDANCY, encodeClientMessage, PROTOCOL_VERSION, readSnapshotHeader, type ClientMessage } from '../../shared/protocol/index.ts';
import { BotScript } from '../../shared/sim/bots.ts';
import { AckCarrier, ClockSync, InputLead, InputSender } from '../lib/client-lib.ts';
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
  /** Index of its room (0 when everyone is in the default room). */
  room: number;
  /** performance.now() and tick of its last snapshot in the window (-1: none yet). */
  lastSnapshotMs: number;
  lastSnapshotTick: number;
  /** The tick of its first snapshot (-1: none yet). */
  firstSnapshotTick: number;
  sync: ClockSync | null;
  lead: InputLead | null;
  sender: InputSender;
  /** Snapshot acks: on the next input message, alone only after a tick without one (protocol 7). */
  acks: AckCarrier;
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
/** Whether the measurement window is open (snapshot gaps count only inside it). */
let measuring = false;

/** One room's snapshots as its bots saw them in the window. */
interface RoomGaps {
  snapshots: number;
  /** Longest time between two snapshots arriving at one of its bots (ms). */
  maxArrivalGapMs: number;
  /** Largest step between the ticks of two snapshots one of its bots received in a row. */
  maxTickStep: number;
}
const roomGaps: RoomGaps[] = Array.from({ length: Math.max(1, rooms) }, () => ({ snapshots: 0, maxArrivalGapMs: 0, maxTickStep: 0 }));

function sawSnapshot(b: LightBot, tick: number, nowMs: number): void {
  if (measuring) {
    const g = roomGaps[b.room];
    g.snapshots++;
    if (b.lastSnapshotMs >= 0) {
      g.maxArrivalGapMs = Math.max(g.maxArrivalGapMs, nowMs - b.lastSnapshotMs);
      g.maxTickStep = Math.max(g.maxTickStep, tick - b.lastSnapshotTick);
    }
  }
  b.lastSnapshotMs = nowMs;
  b.lastSnapshotTick = tick;
  if (b.firstSnapshotTick < 0) b.firstSnapshotTick = tick;
}

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
    sawSnapshot(b, b.snapshotTick, now);
    b.acks.decoded(b.snapshotTick);
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
  const bot: LightBot = { ws, room: rooms > 0 ? i % rooms : 0, lastSnapshotMs: -1, lastSnapshotTick: -1, firstSnapshotTick: -1, sync: null, lead: null, sender: new InputSender({ redundancy: DEFAULT_INPUT_REDUNDANCY }), acks: new AckCarrier(), missedInputTicks: null, pingsSent: 0, nextPingMs: 0, closed: false, snapshotTick: null };
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
    const msg = target < 0 ? null : b.sender.update(target);
    if (msg !== null) {
      const ackTick = b.acks.carry();
      if (ackTick !== undefined) msg.ackTick = ackTick;
      send(b, msg);
      sent.input++;
    } else {
      const ackTick = b.acks.alone();
      if (ackTick === null) continue;
      send(b, { type: 'ack', tick: ackTick });
      sent.ack++;
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

/** Longest the settle waits for the rooms to run their settle ticks. */
const SETTLE_LIMIT_MS = 60_000;
const settleTicks = Math.round(settleMs / TICK_MS);
const settleStartMs = performance.now();
await new Promise((r) => setTimeout(r, settleMs));
while (performance.now() - settleStartMs < SETTLE_LIMIT_MS && bots.some((b) => b.firstSnapshotTick < 0 || b.lastSnapshotTick - b.firstSnapshotTick < settleTicks)) {
  await new Promise((r) => setTimeout(r, 100));
}
const settledMs = performance.now() - settleStartMs;
const loopDelay = monitorEventLoopDelay({ resolution: 5 });
loopDelay.enable();
for (const b of bots) b.lastSnapshotMs = -1;
measuring = true;
const start = { atMs: performance.now(), cpu: process.cpuUsage(), sent: { ...sent }, received: { ...received } };
say({ window: true });
await new Promise((r) => setTimeout(r, windowMs));
measuring = false;
loopDelay.disable();
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
    /** How long the settle took (more than SETTLE_MS when the rooms ran slower than 60 ticks/s). */
    settledMs,
    protocolErrors,
    cpuShare: (cpu.user + cpu.system) / 1e6 / seconds,
    /** The swarm's own event-loop delay in the window (ms): large values mean the bots, not the server, were late. */
    loopDelayMs: { p99: loopDelay.percentile(99) / 1e6, max: loopDelay.max / 1e6 },
    rooms: rooms > 0 ? roomGaps.map((g, i) => ({ id: `r${i + 1}`, ...g })) : [],
  },
});
// Stay connected and sending while the server reports its side of the window (the figure then stops this process).
function leave(): void {
  clearInterval(steer);
  clearInterval(pumper);
  let open = 0;
  for (const b of bots) {
    if (b.ws.readyState === WebSocket.CLOSED) continue;
    open++;
    b.ws.once('close', () => {
      if (--open === 0) process.exit(0);
    });
    b.ws.close(1000, 'bench done');
  }
  if (open === 0) process.exit(0);
  setTimeout(() => process.exit(0), 2000).unref();
}
process.once('SIGTERM', leave);
setTimeout(leave, 5000);
