// End-to-end server benchmark: the real server (HTTP + ws on loopback) runs cubes-901 with 60 Hz snapshots while N
// WebSocket clients join; client 1 ploughs the big cube through the field. Reports bytes per snapshot and kbps per
// client as received on the sockets, plus the server's tick timing (whole tick and physics step).
// Run: node_modules/.bin/node bench/server-bandwidth.ts [seconds=20] [clients=4] [snapshotHz=60] [--json]
import WebSocket from 'ws';
import { silentLogger } from '../server/logger.ts';
import { startServer } from '../server/start-server.ts';
import { TICK_MS } from '../shared/tick-rate.ts';
import {
  decodeServerMessage,
  encodeClientMessage,
  PROTOCOL_VERSION,
  readSnapshotHeader,
  snapshotFormatFromSpec,
  SnapshotDecoder,
  type ClientMessage,
} from '../shared/protocol/index.ts';

const args = process.argv.slice(2).filter((a) => !a.startsWith('--'));
const json = process.argv.includes('--json');
const seconds = Number(args[0] ?? 20);
const clientCount = Number(args[1] ?? 4);
const snapshotHz = Number(args[2] ?? 60);
const warmupSeconds = 2;

interface BenchClient {
  ws: WebSocket;
  playerId: number;
  snapshotBytes: number;
  snapshots: number;
  fullSnapshots: number;
  otherBytes: number;
  lastTick: number;
  measuring: boolean;
  welcomeBytes: number;
  firstSnapshotBytes: number;
}

function send(ws: WebSocket, m: ClientMessage): void {
  if (ws.readyState === WebSocket.OPEN) ws.send(encodeClientMessage(m));
}

async function connect(url: string, name: string, decodeAll: boolean): Promise<BenchClient> {
  const ws = new WebSocket(url);
  const c: BenchClient = { ws, playerId: 0, snapshotBytes: 0, snapshots: 0, fullSnapshots: 0, otherBytes: 0, lastTick: 0, measuring: false, welcomeBytes: 0, firstSnapshotBytes: 0 };
  let decoder: SnapshotDecoder | null = null;
  await new Promise<void>((resolve, reject) => {
    ws.once('open', () => resolve());
    ws.once('error', reject);
  });
  const welcomed = new Promise<void>((resolve) => {
    ws.on('message', (data: Buffer) => {
      const bytes = new Uint8Array(data.buffer, data.byteOffset, data.byteLength);
      const r = decodeServerMessage(bytes);
      if (!r.ok) throw new Error(`bad server message: ${r.error}`);
      const m = r.message;
      if (m.type === 'welcome') {
        c.playerId = m.playerId;
        c.welcomeBytes = data.byteLength;
        if (decodeAll) decoder = new SnapshotDecoder(snapshotFormatFromSpec(m.scenario.bounds, m.snapshotFormat));
        resolve();
      }
      if (m.type === 'snapshot') {
        const header = readSnapshotHeader(m.bytes, c.lastTick > 0 ? c.lastTick : null);
        if (c.firstSnapshotBytes === 0) c.firstSnapshotBytes = data.byteLength;
        if (decoder) decoder.decode(m.bytes); // client 1 decodes everything (a real client's work); others only ack
        c.lastTick = header.tick;
        if (c.measuring) {
          c.snapshots++;
          c.snapshotBytes += data.byteLength;
          if (header.baselineTick === null) c.fullSnapshots++;
        }
        send(ws, { type: 'ack', tick: header.tick });
      } else if (c.measuring) c.otherBytes += data.byteLength;
    });
  });
  send(ws, { type: 'hello', version: PROTOCOL_VERSION, name, room: null });
  await welcomed;
  return c;
}

function quantile(sorted: number[], q: number): number {
  if (sorted.length === 0) return 0;
  return sorted[Math.min(sorted.length - 1, Math.floor(q * sorted.length))];
}

// Every client comes from 127.0.0.1: lift the per-address connection caps.
const server = await startServer({ port: 0, scenario: 'cubes-901', snapshotRateHz: snapshotHz, logger: silentLogger(), maxClients: 64, connectionPolicy: { maxSocketsPerAddress: Infinity, maxPendingPerAddress: Infinity } });
const room = server.game.rooms.local('default')!;
const tickMs: number[] = [];
const stepMs: number[] = [];
let measuringTicks = false;
const tickOnce = room.tickOnce.bind(room);
const sim = room.sim;
const step = sim.step.bind(sim);
sim.step = (record) => {
  const t0 = performance.now();
  const events = step(record);
  if (measuringTicks) stepMs.push(performance.now() - t0);
  return events;
};
room.tickOnce = () => {
  const t0 = performance.now();
  tickOnce();
  if (measuringTicks) tickMs.push(performance.now() - t0);
};

const clients: BenchClient[] = [];
for (let i = 0; i < clientCount; i++) clients.push(await connect(server.wsUrl, `bench-${i}`, i === 0));
// Client 1 drives: full speed into the field, then circles (the busiest case for the cube field); others idle/walk.
let n = 0;
const driver = setInterval(() => {
  n++;
  const tick = room.sim.tick + 3;
  const yaw = n < 150 ? 0 : ((n - 150) * 136) % 65536;
  send(clients[0].ws, { type: 'input', firstTick: tick, commands: [{ moveX: 0, moveZ: 127, yaw, pitch: 0, buttons: 4 }] });
  for (let i = 1; i < clients.length; i++) send(clients[i].ws, { type: 'input', firstTick: tick, commands: [{ moveX: (i * 37) % 255 - 127, moveZ: 60, yaw: (i * 9000) % 65536, pitch: 0, buttons: 0 }] });
}, TICK_MS);

await new Promise((r) => setTimeout(r, warmupSeconds * 1000));
for (const c of clients) c.measuring = true;
measuringTicks = true;
const startTick = room.sim.tick;
const t0 = performance.now();
await new Promise((r) => setTimeout(r, seconds * 1000));
const elapsedS = (performance.now() - t0) / 1000;
measuringTicks = false;
for (const c of clients) c.measuring = false;
const ticksRun = room.sim.tick - startTick;
clearInterval(driver);
for (const c of clients) c.ws.close();
await server.close('bench over');

const per = clients.map((c) => ({
  snapshots: c.snapshots,
  full: c.fullSnapshots,
  bytesPerSnapshot: c.snapshots ? c.snapshotBytes / c.snapshots : 0,
  snapshotKbps: (c.snapshotBytes * 8) / 1000 / elapsedS,
  totalKbps: ((c.snapshotBytes + c.otherBytes) * 8) / 1000 / elapsedS,
}));
tickMs.sort((a, b) => a - b);
stepMs.sort((a, b) => a - b);
const mean = (xs: number[]): number => (xs.length ? xs.reduce((a, b) => a + b, 0) / xs.length : 0);
const result = {
  scenario: 'cubes-901',
  bodies: room.info().bodies,
  clients: clientCount,
  snapshotHz,
  seconds: Math.round(elapsedS * 10) / 10,
  ticksRun,
  tickRateAchievedHz: Math.round((ticksRun / elapsedS) * 100) / 100,
  bytesPerSnapshotMean: Math.round(mean(per.map((p) => p.bytesPerSnapshot))),
  kbpsPerClientMean: Math.round(mean(per.map((p) => p.totalKbps))),
  snapshotKbpsPerClientMean: Math.round(mean(per.map((p) => p.snapshotKbps))),
  snapshotsPerClientPerSecond: Math.round((mean(per.map((p) => p.snapshots)) / elapsedS) * 10) / 10,
  fullSnapshots: per.reduce((a, p) => a + p.full, 0),
  welcomeBytes: clients[0].welcomeBytes,
  firstFullSnapshotBytes: clients[0].firstSnapshotBytes,
  tickMs: { mean: +mean(tickMs).toFixed(3), p50: +quantile(tickMs, 0.5).toFixed(3), p99: +quantile(tickMs, 0.99).toFixed(3), max: +(tickMs.at(-1) ?? 0).toFixed(3) },
  physicsStepMs: { mean: +mean(stepMs).toFixed(3), p50: +quantile(stepMs, 0.5).toFixed(3), p99: +quantile(stepMs, 0.99).toFixed(3) },
  overrunsOver16_7ms: tickMs.filter((t) => t > TICK_MS).length,
};
if (json) console.log(JSON.stringify(result));
else {
  console.log(`cubes-901 (${result.bodies} bodies), ${clientCount} client(s), ${snapshotHz} Hz snapshots, ${result.seconds} s measured (after ${warmupSeconds} s warm-up)`);
  console.log(`  ticks: ${ticksRun} (${result.tickRateAchievedHz} Hz achieved)`);
  console.log(`  snapshot: ${result.bytesPerSnapshotMean} bytes mean (${result.snapshotsPerClientPerSecond}/s per client, ${result.fullSnapshots} full)`);
  console.log(`  per client: ${result.kbpsPerClientMean} kbps total, ${result.snapshotKbpsPerClientMean} kbps snapshots`);
  console.log(`  on join: welcome ${result.welcomeBytes} bytes (scene + ${result.bodies} descriptors), first (full) snapshot ${result.firstFullSnapshotBytes} bytes`);
  console.log(`  tick: mean ${result.tickMs.mean} ms, p50 ${result.tickMs.p50}, p99 ${result.tickMs.p99}, max ${result.tickMs.max}; physics step mean ${result.physicsStepMs.mean} ms, p99 ${result.physicsStepMs.p99}`);
  console.log(`  ticks over 16.7 ms: ${result.overrunsOver16_7ms}`);
}
