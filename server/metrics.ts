// The server's Prometheus metrics: one prom-client Registry per server instance (so several servers in one process,
// as in tests, never share counters), the metric objects rooms and sessions update, and the text for GET /metrics.
import { AggregatorRegistry, Gauge, Histogram, Registry, collectDefaultMetrics, type Counter, type MetricObjectWithValues, type MetricValue } from 'prom-client';
import { talliedCounter } from './tallied-counter.ts';
import { talliedHistogram } from './tallied-histogram.ts';

const TICK_BUCKETS_SECONDS = [0.0005, 0.001, 0.002, 0.004, 0.008, 0.0125, 0.01667, 0.025, 0.05, 0.1, 0.25];
const SNAPSHOT_BYTE_BUCKETS = [64, 256, 1024, 4096, 16384, 65536, 262144];

/** Every metric the server exports. */
export interface ServerMetrics {
  readonly registry: Registry;
  /** Whole tick: inputs, physics, snapshots, sends. */
  readonly tickDuration: Histogram<string>;
  /** Simulation.step alone. */
  readonly physicsStep: Histogram<string>;
  readonly ticks: Counter<string>;
  /** Ticks that took longer than one tick period. */
  readonly tickOverruns: Counter<string>;
  /** Slowdowns: ticks given up because the server could not catch up. */
  readonly ticksSkipped: Counter<string>;
  readonly rooms: Gauge<string>;
  readonly clients: Gauge<string>;
  readonly players: Gauge<string>;
  /** Inputs stamped for a tick already applied. */
  readonly inputsLate: Counter<string>;
  /** Inputs dropped for another reason (reason label: too_far). */
  readonly inputsDropped: Counter<string>;
  /** Ticks on which a player's last input was repeated because none had arrived. */
  readonly inputsRepeated: Counter<string>;
  readonly inputsAccepted: Counter<string>;
  /** Input commands the validator clamped into range (accepted, but the client sent out-of-range values). */
  readonly inputsClamped: Counter<string>;
  readonly snapshotBytes: Histogram<string>;
  /** Snapshots by kind (full, delta). */
  readonly snapshotsSent: Counter<string>;
  /** Snapshots not sent because the client's socket buffer was backed up. */
  readonly snapshotsSkipped: Counter<string>;
  readonly bytesSent: Counter<string>;
  readonly bytesReceived: Counter<string>;
  readonly messagesReceived: Counter<string>;
  /** Messages rejected by validation (reason label). */
  readonly badMessages: Counter<string>;
  /** Clients disconnected by the server (reason label). */
  readonly disconnects: Counter<string>;
  readonly connections: Counter<string>;
  /** Requests, upgrades and hellos refused by access control (reason label: the refusal's code). */
  readonly accessRefused: Counter<string>;
  /** Players taken back by a new connection with their resume token. */
  readonly resumes: Counter<string>;
  /** Exceptions while taking a client's message (that client was disconnected; the server went on). */
  readonly messageErrors: Counter<string>;
  /** Exceptions and rejections that reached the process's last-resort handler (kind label: exception, rejection). */
  readonly uncaughtErrors: Counter<string>;
  /** WebSocket upgrades refused before a session started (reason label: per-address caps, back-off, full). */
  readonly connectionsRefused: Counter<string>;
  /** Each open room's Jolt heap in bytes (labels room, kind = used | free), read at scrape time. */
  readonly wasmHeap: Gauge<string>;
  /** Sets where wasmHeap reads the open rooms from (the server does it once its rooms exist). */
  setRoomHeapSource(source: () => Iterable<RoomHeapUsage>): void;
  /** 1 while a room cannot keep the tick rate and runs slowed, else 0 (label room). */
  readonly roomSlow: Gauge<string>;
  /** Sets where roomSlow reads the open rooms from (their ticks per second are the monitor's taos_room_ticks_per_second). */
  setRoomPaceSource(source: () => Iterable<RoomPaceReading>): void;
}

/** One room's pace for the roomSlow gauge. */
export interface RoomPaceReading {
  room: string;
  slow: boolean;
}

/** One room's heap for the wasmHeap gauge. */
export interface RoomHeapUsage {
  room: string;
  usedBytes: number;
  freeBytes: number;
}

/** Creates a fresh registry with all metrics (plus Node process metrics when `processMetrics`). */
export function createMetrics(opts: { processMetrics?: boolean; prefix?: string } = {}): ServerMetrics {
  const registry = new Registry();
  const p = opts.prefix ?? 'taos_';
  const registers = [registry];
  if (opts.processMetrics ?? true) collectDefaultMetrics({ register: registry, prefix: p });
  // Counters are summed in place and handed to prom-client when it collects (talliedCounter): several are counted per
  // message or per member and tick.
  const counter = (name: string, help: string, labelNames: string[] = []): Counter<string> => talliedCounter({ name: p + name, help, labelNames, registers });
  // Histograms observed once or more per tick store plain values until prom-client collects (talliedHistogram).
  const gauge = (name: string, help: string): Gauge<string> => new Gauge({ name: p + name, help, registers });
  let heapSource: () => Iterable<RoomHeapUsage> = () => [];
  const wasmHeap = new Gauge({
    name: `${p}room_wasm_heap_bytes`,
    help: "Each open room's Jolt WASM heap (its own 128 MiB module): used and free bytes",
    labelNames: ['room', 'kind'],
    registers,
    collect() {
      // Closed rooms disappear from the exposition: at most --max-rooms rooms are ever labelled at once.
      this.reset();
      for (const r of heapSource()) {
        this.set({ room: r.room, kind: 'used' }, r.usedBytes);
        this.set({ room: r.room, kind: 'free' }, r.freeBytes);
      }
    },
  });
  let paceSource: () => Iterable<RoomPaceReading> = () => [];
  const roomSlow = new Gauge({
    name: `${p}room_slow`,
    help: ' 1 while a room cannot keep the tick rate and runs slowed (only that room), else 0',
    labelNames: ['room'],
    registers,
    collect() {
      this.reset();
      for (const r of paceSource()) this.set({ room: r.room }, r.slow ? 1 : 0);
    },
  });
  return {
    registry,
    wasmHeap,
    setRoomHeapSource: (source) => {
      heapSource = source;
    },
    roomSlow,
    setRoomPaceSource: (source) => {
      paceSource = source;
    },
    tickDuration: talliedHistogram({ name: `${p}tick_duration_seconds`, help: 'Wall time of one room tick (inputs, physics, snapshots, sends)', buckets: TICK_BUCKETS_SECONDS, registers }),
    physicsStep: talliedHistogram({ name: `${p}physics_step_seconds`, help: 'Wall time of Simulation.step in one room tick', buckets: TICK_BUCKETS_SECONDS, registers }),
    ticks: counter('ticks_total', 'Room ticks simulated'),
    tickOverruns: counter('tick_overruns_total', 'Room ticks that took longer than the tick period'),
    ticksSkipped: counter('ticks_skipped_total', 'Ticks given up (slowdown) because a room could not catch up'),
    rooms: gauge('rooms', 'Open rooms'),
    clients: gauge('clients', 'Connected WebSocket clients'),
    players: gauge('players', 'Players in rooms'),
    inputsLate: counter('inputs_late_total', 'Inputs stamped for a tick that was already applied (dropped)'),
    inputsDropped: counter('inputs_dropped_total', 'Inputs dropped for a reason other than being late', ['reason']),
    inputsRepeated: counter('inputs_repeated_total', "Player ticks that repeated the last input because none had arrived"),
    inputsAccepted: counter('inputs_accepted_total', 'Inputs stored for a future tick'),
    inputsClamped: counter('inputs_clamped_total', 'Input commands clamped into range by validation'),
    snapshotBytes: talliedHistogram({ name: `${p}snapshot_bytes`, help: 'Encoded size of one snapshot message', buckets: SNAPSHOT_BYTE_BUCKETS, registers }),
    snapshotsSent: counter('snapshots_sent_total', 'Snapshots sent', ['kind']),
    snapshotsSkipped: counter('snapshots_skipped_total', "Snapshots skipped because the client's socket buffer was backed up"),
    bytesSent: counter('bytes_sent_total', 'Bytes sent to clients (all messages)'),
    bytesReceived: counter('bytes_received_total', 'Bytes received from clients'),
    messagesReceived: counter('messages_received_total', 'Messages received from clients'),
    badMessages: counter('bad_messages_total', 'Messages rejected by validation', ['reason']),
    disconnects: counter('disconnects_total', 'Clients disconnected by the server', ['reason']),
    connections: counter('connections_total', 'WebSocket connections accepted'),
    accessRefused: counter('access_refused_total', 'Requests, WebSocket upgrades and hellos refused by access control', ['reason']),
    resumes: counter('resumes_total', 'Players taken back by a new connection with their resume token'),
    messageErrors: counter('message_errors_total', "Exceptions while handling a client's message (the client was disconnected)"),
    uncaughtErrors: counter('uncaught_errors_total', "Exceptions and promise rejections caught by the serving process's last-resort handler", ['kind']),
    connectionsRefused: counter('connections_refused_total', 'WebSocket upgrades refused before a session started', ['reason']),
  };
}

/** The Prometheus text exposition of a registry, with its content type. */
export async function renderMetrics(metrics: ServerMetrics): Promise<{ body: string; contentType: string }> {
  return { body: await metrics.registry.metrics(), contentType: metrics.registry.contentType };
}

/** The exposition of `metrics` summed with other threads' registries (prom-client JSON from the room workers). */
export async function renderMergedMetrics(metrics: ServerMetrics, others: readonly unknown[]): Promise<{ body: string; contentType: string }> {
  if (others.length === 0) return renderMetrics(metrics);
  const own = await metrics.registry.getMetricsAsJSON();
  const merged = AggregatorRegistry.aggregate([own, ...(others as Array<Array<MetricObjectWithValues<MetricValue<string>>>>)]);
  return { body: await merged.metrics(), contentType: metrics.registry.contentType };
}
