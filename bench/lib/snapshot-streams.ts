// One client's downstream for the bandwidth figure, at several snapshot rates at once: our per-client SnapshotEncoder
// (acks back after a round trip, every snapshot decoded and checked bit-exact), optionally beside the plain-msgpackr
// and @colyseus/schema baselines fed the same quantized state. Bytes are counted per named phase of the run.
import { dequantizeFrame, encodeServerMessage, framesEqual, quantizeFrame, SnapshotDecoder, SnapshotEncoder, type QuantizedFrame, type SnapshotFormat, type SnapshotView } from '../../shared/protocol/index.ts';
import type { Simulation } from '../../shared/sim/simulation.ts';
import type { SimEvent } from '../../shared/sim/types.ts';
import { ColyseusStream, naiveSnapshotBytes } from './baseline-encoders.ts';
import { wsFrameBytes } from './wire.ts';

/** Bytes and counts of one phase at one rate (sizes on the wire: WebSocket framing included). */
export interface PhaseCounters {
  ticks: number;
  snapshotBytes: number;
  snapshots: number;
  fullSnapshots: number;
  /** Events go to every client reliably whatever the rate: the same bytes at every rate. */
  eventBytes: number;
  naiveBytes: number;
  colyseusBytes: number;
  colyseusPatches: number;
  /** Time in SnapshotEncoder.encode (the server's per-client work, unshared) and SnapshotDecoder.decode (µs, summed). */
  encodeUs: number;
  decodeUs: number;
}

function zero(): PhaseCounters {
  return { ticks: 0, snapshotBytes: 0, snapshots: 0, fullSnapshots: 0, eventBytes: 0, naiveBytes: 0, colyseusBytes: 0, colyseusPatches: 0, encodeUs: 0, decodeUs: 0 };
}

interface RateStream {
  rateHz: number;
  accumulator: number;
  encoder: SnapshotEncoder;
  decoder: SnapshotDecoder;
  acks: Array<{ atTick: number; tick: number }>;
  colyseus: ColyseusStream | null;
  phases: Map<string, PhaseCounters>;
}

/** One client's snapshot streams over a simulation, one per rate. */
export class SnapshotStreams {
  private readonly streams: RateStream[];
  private readonly format: SnapshotFormat;
  private readonly rttTicks: number;
  private ticks = 0;

  /** `knownIds`: bodies whose descriptors the welcome carried; `baselines`: also run the msgpackr and Colyseus baselines. */
  constructor(opts: { format: SnapshotFormat; ratesHz: readonly number[]; rttTicks: number; knownIds: readonly number[]; baselines: boolean }) {
    this.format = opts.format;
    this.rttTicks = opts.rttTicks;
    this.streams = opts.ratesHz.map((rateHz) => {
      const encoder = new SnapshotEncoder(opts.format);
      encoder.markDescriptorsKnown(opts.knownIds);
      return { rateHz, accumulator: 0, encoder, decoder: new SnapshotDecoder(opts.format), acks: [], colyseus: opts.baselines ? new ColyseusStream() : null, phases: new Map() };
    });
  }

  /** After a sim.step(): counts the tick's events and sends each stream's snapshot if one is due, all under `phase`. */
  afterStep(sim: Simulation, tick: number, events: readonly SimEvent[], phase: string): void {
    const eventBytes = events.length > 0 ? wsFrameBytes(encodeServerMessage({ type: 'events', events: events as SimEvent[] }).length) : 0;
    let frame: QuantizedFrame | null = null;
    let view: SnapshotView | null = null;
    const t = this.ticks++;
    for (const s of this.streams) {
      const c = counters(s, phase);
      c.ticks++;
      c.eventBytes += eventBytes;
      // The room's rule: a frame goes out on ticks where the running count crosses a whole number.
      s.accumulator += s.rateHz;
      if (s.accumulator + 1e-9 < 60) continue;
      s.accumulator -= 60;
      frame ??= quantizeFrame(this.format, tick, sim.readBodyStates(), sim.characters());
      while (s.acks.length > 0 && s.acks[0].atTick <= t) s.encoder.acknowledge(s.acks.shift()!.tick);
      const t0 = performance.now();
      const encoded = s.encoder.encode(frame, (id) => sim.bodyDescriptor(id));
      const t1 = performance.now();
      const message = encodeServerMessage({ type: 'snapshot', bytes: encoded.bytes, descriptors: encoded.descriptors });
      c.snapshotBytes += wsFrameBytes(message.length);
      c.snapshots++;
      if (encoded.baselineTick === null) c.fullSnapshots++;
      const t2 = performance.now();
      const decoded = s.decoder.decode(encoded.bytes);
      c.decodeUs += (performance.now() - t2) * 1000;
      c.encodeUs += (t1 - t0) * 1000;
      if (!framesEqual(decoded.frame, frame)) throw new Error(`bandwidth: the ${s.rateHz} Hz snapshot of tick ${tick} did not decode to the frame sent`);
      s.acks.push({ atTick: t + this.rttTicks, tick });
      if (s.colyseus) {
        view ??= dequantizeFrame(this.format, frame);
        c.naiveBytes += wsFrameBytes(naiveSnapshotBytes(view));
        const patch = s.colyseus.update(view);
        if (patch > 0) {
          c.colyseusBytes += wsFrameBytes(patch);
          c.colyseusPatches++;
        }
      }
    }
  }

  /** One phase's counters at one rate (zeros when the phase never ran). */
  phase(rateHz: number, phase: string): PhaseCounters {
    const s = this.streams.find((x) => x.rateHz === rateHz);
    if (!s) throw new Error(`SnapshotStreams: no ${rateHz} Hz stream`);
    return { ...(s.phases.get(phase) ?? zero()) };
  }

  /** Several phases' counters at one rate, summed. */
  phases(rateHz: number, names: readonly string[]): PhaseCounters {
    const out = zero();
    for (const n of names) {
      const c = this.phase(rateHz, n);
      for (const k of Object.keys(out) as Array<keyof PhaseCounters>) out[k] += c[k];
    }
    return out;
  }
}

function counters(s: RateStream, phase: string): PhaseCounters {
  let c = s.phases.get(phase);
  if (!c) s.phases.set(phase, (c = zero()));
  return c;
}
