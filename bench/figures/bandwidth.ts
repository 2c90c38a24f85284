// Bandwidth: cubes-901 with its scripted rolling player cube, 60 s of simulation; per-client downstream kbps for our
// per-client delta codec (acks back after a 100 ms round trip, every snapshot decoded and checked bit-exact) against
// plain msgpackr of every body's float pose and @colyseus/schema delta patches of the same state, at 60 and 20 Hz.
import { createSnapshotFormat, dequantizeFrame, encodeServerMessage, framesEqual, quantizeFrame, SnapshotDecoder, SnapshotEncoder, type QuantizedFrame, type SnapshotView } from '../../shared/protocol/index.ts';
import { getScenario } from '../../scenarios/index.ts';
import { BodyFlag } from '../../shared/physics/index.ts';
import { TICK_MS, TICK_RATE_HZ } from '../../shared/tick-rate.ts';
import { ColyseusStream, naiveSnapshotBytes } from '../lib/baseline-encoders.ts';
import type { FigureImpl, FigureOutput } from '../lib/figure.ts';
import { botRecords, createSceneSim, CUBES_SCENE } from '../lib/scenes.ts';
import { round } from '../lib/stats.ts';
import { kbps, wsFrameBytes } from '../lib/wire.ts';

const RATES_HZ = [60, 30, 20] as const;
const RTT_MS = 100;
const RTT_TICKS = Math.round(RTT_MS / TICK_MS);
const GOAL_KBPS = 128;

interface OurStream {
  rateHz: number;
  accumulator: number;
  encoder: SnapshotEncoder;
  decoder: SnapshotDecoder;
  acks: Array<{ atTick: number; tick: number }>;
  bytes: number;
  snapshots: number;
  full: number;
  naiveBytes: number;
  colyseus: ColyseusStream;
  colyseusBytes: number;
  colyseusMessages: number;
}

function due(s: OurStream): boolean {
  // The room's rule: a frame goes out on ticks where the running count crosses a whole number.
  s.accumulator += s.rateHz;
  if (s.accumulator + 1e-9 < TICK_RATE_HZ) return false;
  s.accumulator -= TICK_RATE_HZ;
  return true;
}

async function run(opts: { quick: boolean; log(m: string): void }): Promise<FigureOutput> {
  const seconds = opts.quick ? 20 : 60;
  const ticks = seconds * TICK_RATE_HZ;
  const def = getScenario(CUBES_SCENE.scenario);
  const sim = await createSceneSim(CUBES_SCENE);
  try {
    const format = createSnapshotFormat(def.bounds);
    // The welcome carried the descriptors of every moving body alive at tick 0.
    const initial = sim.descriptors().filter((d) => d.motion !== 'static').map((d) => d.id);
    const streams: OurStream[] = RATES_HZ.map((rateHz) => {
      const encoder = new SnapshotEncoder(format);
      encoder.markDescriptorsKnown(initial);
      return { rateHz, accumulator: 0, encoder, decoder: new SnapshotDecoder(format), acks: [], bytes: 0, snapshots: 0, full: 0, naiveBytes: 0, colyseus: new ColyseusStream(), colyseusBytes: 0, colyseusMessages: 0 };
    });
    const bots = botRecords(1);
    let eventBytes = 0;
    let maxMoving = 0;
    opts.log(`${CUBES_SCENE.label}: ${seconds} s of simulation, snapshots at ${RATES_HZ.join('/')} Hz, acks after ${RTT_MS} ms`);
    for (let t = 0; t < ticks; t++) {
      const record = bots.next();
      const events = sim.step(record);
      if (events.length > 0) eventBytes += wsFrameBytes(encodeServerMessage({ type: 'events', events }).length);
      const read = sim.readBodyStates();
      let moving = 0;
      for (let i = 0; i < read.count; i++) if ((read.flags[i] & BodyFlag.Static) === 0) moving++;
      maxMoving = Math.max(maxMoving, moving);
      let frame: QuantizedFrame | null = null;
      let view: SnapshotView | null = null;
      for (const s of streams) {
        if (!due(s)) continue;
        frame ??= quantizeFrame(format, record.tick, read, sim.characters());
        view ??= dequantizeFrame(format, frame);
        while (s.acks.length > 0 && s.acks[0].atTick <= t) s.encoder.acknowledge(s.acks.shift()!.tick);
        const encoded = s.encoder.encode(frame, (id) => sim.bodyDescriptor(id));
        const message = encodeServerMessage({ type: 'snapshot', bytes: encoded.bytes, descriptors: encoded.descriptors });
        s.bytes += wsFrameBytes(message.length);
        s.snapshots++;
        if (encoded.baselineTick === null) s.full++;
        const decoded = s.decoder.decode(encoded.bytes);
        if (!framesEqual(decoded.frame, frame)) throw new Error(`bandwidth: the ${s.rateHz} Hz snapshot of tick ${record.tick} did not decode to the frame sent`);
        s.acks.push({ atTick: t + RTT_TICKS, tick: record.tick });
        s.naiveBytes += wsFrameBytes(naiveSnapshotBytes(view));
        const patch = s.colyseus.update(view);
        if (patch > 0) {
          s.colyseusBytes += wsFrameBytes(patch);
          s.colyseusMessages++;
        }
      }
    }
    const byRate = new Map(streams.map((s) => [s.rateHz, s]));
    const k = (bytes: number): number => round(kbps(bytes, seconds), 1);
    const s60 = byRate.get(60)!;
    const s20 = byRate.get(20)!;
    const detail = {
      scene: CUBES_SCENE,
      seconds,
      rttMs: RTT_MS,
      movingBodiesMax: maxMoving,
      eventsKbps: k(eventBytes),
      rates: streams.map((s) => ({
        rateHz: s.rateHz,
        oursKbps: k(s.bytes),
        oursMeanSnapshotBytes: round(s.bytes / s.snapshots, 1),
        fullSnapshots: s.full,
        snapshots: s.snapshots,
        naiveKbps: k(s.naiveBytes),
        colyseusKbps: k(s.colyseusBytes),
        colyseusPatches: s.colyseusMessages,
        oursTotalWithEventsKbps: k(s.bytes + eventBytes),
      })),
    };
    return {
      headline: {
        kbpsPerClient60Hz: k(s60.bytes),
        kbpsPerClient20Hz: k(s20.bytes),
        naiveKbps60Hz: k(s60.naiveBytes),
        colyseusKbps60Hz: k(s60.colyseusBytes),
      },
      detail,
      rows: [
        { figure: 'bandwidth', measure: `ours, 60 Hz snapshots (${CUBES_SCENE.label}, ${seconds} s)`, value: kbps(s60.bytes, seconds), unit: 'kbps', digits: 1, goal: { op: '<=', value: GOAL_KBPS } },
        { figure: 'bandwidth', measure: 'ours, 20 Hz snapshots', value: kbps(s20.bytes, seconds), unit: 'kbps', digits: 1 },
        { figure: 'bandwidth', measure: 'plain msgpackr of every body, 60 Hz', value: kbps(s60.naiveBytes, seconds), unit: 'kbps', digits: 0 },
        { figure: 'bandwidth', measure: '@colyseus/schema deltas, 60 Hz', value: kbps(s60.colyseusBytes, seconds), unit: 'kbps', digits: 1 },
        { figure: 'bandwidth', measure: '@colyseus/schema deltas, 20 Hz', value: kbps(s20.colyseusBytes, seconds), unit: 'kbps', digits: 1 },
        { figure: 'bandwidth', measure: 'events (reliable, every client, any rate)', value: kbps(eventBytes, seconds), unit: 'kbps', digits: 1 },
      ],
      charts: [
        {
          title: `Bandwidth per client, ${CUBES_SCENE.label}, ${seconds} s (kbps incl. WebSocket framing)`,
          unit: 'kbps (log)',
          log: true,
          goal: GOAL_KBPS,
          bars: [
            { label: 'ours, 60 Hz', value: kbps(s60.bytes, seconds), series: 'ours' },
            { label: '@colyseus/schema, 60 Hz', value: kbps(s60.colyseusBytes, seconds), series: 'baseline' },
            { label: 'plain msgpackr, 60 Hz', value: kbps(s60.naiveBytes, seconds), series: 'baseline' },
            { label: 'ours, 20 Hz', value: kbps(s20.bytes, seconds), series: 'ours' },
            { label: '@colyseus/schema, 20 Hz', value: kbps(s20.colyseusBytes, seconds), series: 'baseline' },
            { label: 'plain msgpackr, 20 Hz', value: kbps(s20.naiveBytes, seconds), series: 'baseline' },
          ],
        },
      ],
      notes: [
        `${CUBES_SCENE.label} (up to ${maxMoving} moving bodies) driven by one scripted bot (player 1 rolls the big cube, walks, jumps, fires), seed 1, ${seconds} s at 60 Hz.`,
        `Ours: the snapshot message (msgpack envelope + bit-packed delta against the newest acked frame, descriptors of spawned bodies) plus the WebSocket header; acks arrive ${RTT_MS} ms (${RTT_TICKS} ticks) after each snapshot; every snapshot was decoded and matched the server's frame bit for bit.`,
        'Plain msgpackr: [opcode, tick, [[id, x, y, z, qx, qy, qz, qw]…], characters] with float32 numbers, every snapshot. Colyseus: a Schema with a MapSchema of bodies (float32 fields, the same quantized values), one patch per snapshot tick over its reliable stream (empty patches not sent), plus its 1-byte protocol code.',
        'Events (joins, spawns, removals, sensors) go to every client reliably whatever the snapshot rate; they are listed apart and are not in the codec comparison.',
      ],
    };
  } finally {
    sim.destroy();
  }
}

/** The bandwidth figure. */
export const figure: FigureImpl = { run };
