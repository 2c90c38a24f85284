// Snapshot bandwidth: runs cubes-901 (900 cubes and a big cube player 1 rolls through them) and encodes per-client
// delta snapshots at 60, 30 and 20 Hz with acks arriving one RTT after each send; every snapshot is decoded and
// checked bit-exact. Prints bytes per snapshot and kbps per client by phase.
// Run: node_modules/.bin/node bench/snapshot-bytes.ts [seconds=30] [rttMs=100] [driver=bot|plough]
//   bot: the seeded scripted bot (walks, strafes, idles, fires); plough: full speed into the field, then circles of
//   ~8 m radius inside it, so the big cube keeps ploughing through cubes (the busiest case).
import '../server/physics-node.ts';
import { scenario } from '../scenarios/cubes-901.ts';
import { encodeServerMessage } from '../shared/protocol/codec.ts';
import { createSnapshotFormat } from '../shared/protocol/quantization.ts';
import { framesEqual, quantizeFrame } from '../shared/protocol/snapshot-frame.ts';
import { SnapshotDecoder, SnapshotEncoder } from '../shared/protocol/snapshot-stream.ts';
import { BotScript } from '../shared/sim/bots.ts';
import { Simulation } from '../shared/sim/simulation.ts';
import type { TickInputRecord } from '../shared/sim/types.ts';
import { TICK_MS, TICK_RATE_HZ } from '../shared/tick-rate.ts';

/** Player 1 holds forward and sprints: straight into the field for 2.5 s, then turning a full circle every 8 s. */
function ploughRecord(tick: number): TickInputRecord {
  return {
    tick,
    leaves: [],
    joins: tick === 0 ? [{ playerId: 1, name: 'plough' }] : [],
    commands: [{ playerId: 1, input: { moveX: 0, moveZ: 127, yaw: tick < 150 ? 0 : ((tick - 150) * 136) % 65536, pitch: 0, buttons: 4 } }],
  };
}

const seconds = Number(process.argv[2] ?? 30);
const rttMs = Number(process.argv[3] ?? 100);
const ticks = Math.round(seconds * TICK_RATE_HZ);
const ackDelayTicks = Math.round(rttMs / TICK_MS);
const driver = process.argv[4] ?? 'bot';
if (driver !== 'bot' && driver !== 'plough') throw new Error(`driver must be bot or plough, got ${driver}`);
const rates = [60, 30, 20];

interface Stream {
  rateHz: number;
  every: number;
  enc: SnapshotEncoder;
  dec: SnapshotDecoder;
  acks: Array<{ at: number; tick: number }>;
  samples: Array<{ tick: number; payload: number; wire: number; full: boolean; awake: number }>;
}

function wsHeaderBytes(n: number): number {
  return n <= 125 ? 2 : n <= 65535 ? 4 : 10;
}

const sim = await Simulation.create({ scenario, seed: 1 });
const bots = new BotScript({ seed: 1, bots: 1, joinTicks: [0] });
const format = createSnapshotFormat(scenario.bounds);
const streams: Stream[] = rates.map((rateHz) => {
  const enc = new SnapshotEncoder(format);
  // The welcome carried every dynamic body alive at tick 0.
  enc.markDescriptorsKnown(sim.descriptors().filter((d) => d.motion !== 'static').map((d) => d.id));
  return { rateHz, every: TICK_RATE_HZ / rateHz, enc, dec: new SnapshotDecoder(format), acks: [], samples: [] };
});

let encodeMs = 0;
let quantizeMs = 0;
let decodeMs = 0;
let encodes = 0;
let stepMs = 0;
for (let t = 0; t < ticks; t++) {
  let start = performance.now();
  const record = driver === 'bot' ? bots.next() : ploughRecord(sim.tick);
  sim.step(record);
  stepMs += performance.now() - start;
  const tick = sim.tick;
  const read = sim.readBodyStates();
  const characters = sim.characters();
  start = performance.now();
  const frame = quantizeFrame(format, tick, read, characters);
  quantizeMs += performance.now() - start;
  let awake = 0;
  for (let i = 0; i < frame.bodyIds.length; i++) if (frame.bodies[i * 8 + 7] === 0) awake++;
  for (const s of streams) {
    while (s.acks.length > 0 && s.acks[0].at <= tick) s.enc.acknowledge(s.acks.shift()!.tick);
    if (tick % s.every !== 0 || !s.enc.shouldSend(tick)) continue;
    start = performance.now();
    const out = s.enc.encode(frame, (id) => sim.bodyDescriptor(id));
    const msg = encodeServerMessage({ type: 'snapshot', bytes: out.bytes, descriptors: out.descriptors });
    encodeMs += performance.now() - start;
    start = performance.now();
    const decoded = s.dec.decode(out.bytes).frame;
    decodeMs += performance.now() - start;
    encodes++;
    if (!framesEqual(decoded, frame)) throw new Error(`tick ${tick}: decoded frame differs from the server's`);
    s.samples.push({ tick, payload: msg.length, wire: msg.length + wsHeaderBytes(msg.length), full: out.baselineTick === null, awake });
    s.acks.push({ at: tick + ackDelayTicks, tick });
  }
}

const frameBodies = quantizeFrame(format, sim.tick, sim.readBodyStates(), sim.characters()).bodyIds.length;
sim.destroy();

function pct(sorted: number[], p: number): number {
  return sorted.length === 0 ? 0 : sorted[Math.min(sorted.length - 1, Math.floor(p * sorted.length))];
}

const phases: Array<[string, number, number]> = [
  ['0–2 s (join: one full snapshot, then deltas)', 0, 120],
  ['2–10 s', 120, 600],
  [`10–${seconds} s`, 600, ticks + 1],
  [`whole ${seconds} s`, 0, ticks + 1],
];
console.log(`cubes-901, driver ${driver}, ${seconds} s, ${frameBodies} bodies in the last snapshot, acks after ${rttMs} ms (${ackDelayTicks} ticks); bytes = msgpack message (+ WebSocket header for kbps)`);
for (const s of streams) {
  console.log(`\n${s.rateHz} Hz snapshots: ${s.enc.stats.full} full, ${s.enc.stats.delta} delta`);
  console.log('phase'.padEnd(52), 'mean B'.padStart(8), 'p50 B'.padStart(8), 'p95 B'.padStart(8), 'max B'.padStart(8), 'kbps'.padStart(8), 'awake'.padStart(7));
  for (const [name, from, to] of phases) {
    const sel = s.samples.filter((x) => x.tick >= from && x.tick < to);
    if (sel.length === 0) continue;
    const payload = sel.map((x) => x.payload).sort((a, b) => a - b);
    const wireMean = sel.reduce((n, x) => n + x.wire, 0) / sel.length;
    const mean = payload.reduce((n, x) => n + x, 0) / payload.length;
    const kbps = (wireMean * s.rateHz * 8) / 1000;
    const awake = sel.reduce((n, x) => n + x.awake, 0) / sel.length;
    console.log(name.padEnd(52), mean.toFixed(1).padStart(8), String(pct(payload, 0.5)).padStart(8), String(pct(payload, 0.95)).padStart(8), String(payload[payload.length - 1]).padStart(8), kbps.toFixed(1).padStart(8), awake.toFixed(0).padStart(7));
  }
}
console.log(`\nphysics ${(stepMs / ticks).toFixed(2)} ms/tick; quantize ${(quantizeMs / ticks).toFixed(3)} ms/tick (once for all clients)`);
console.log(`per snapshot: encode + frame ${(encodeMs / encodes).toFixed(3)} ms, client decode ${(decodeMs / encodes).toFixed(3)} ms`);
