// In-process server harness for tests: a GameServer on a ManualClock with real Simulations, and protocol-level test
// clients over its MemoryNetwork that decode every server message and snapshot (acking them) exactly as a client would.
import '../../server/physics-node.ts';
import type { SeatTokens } from '../../server/access/seat-tokens.ts';
import type { SessionLimits } from '../../server/session-context.ts';
import { GameServer } from '../../server/game-server.ts';
import { silentLogger, type Logger } from '../../server/logger.ts';
import { memoryPeerConnection } from '../../server/memory-peer.ts';
import type { NetModeRequest } from '../../server/net-mode-policy.ts';
import type { DurabilityOptions } from '../../server/recorder.ts';
import { MemoryNetwork, type MemoryNetworkOptions, type MemoryTransport } from '../../sdk/index.ts';
import { createMetrics } from '../../server/metrics.ts';
import { createRoomFactory, type ScenarioSource } from '../../server/room-factory.ts';
import type { Room } from '../../server/room.ts';
import {
  decodeServerMessage,
  encodeClientMessage,
  PROTOCOL_VERSION,
  snapshotFormatFromSpec,
  SnapshotDecoder,
  type QuantizedFrame,
  type ServerMessage,
  type WelcomeMessage,
} from '../../shared/protocol/index.ts';
import { ManualClock } from '../../shared/clock.ts';
import type { InputCommand } from '../../shared/sim/input.ts';
import type { ScenarioDefinition } from '../../shared/sim/scenario.ts';
import type { SimEvent, TickInputRecord } from '../../shared/sim/types.ts';
import { TICK_MS } from '../../shared/tick-rate.ts';

/** One tick period in ms (tests import it from here). */
export { TICK_MS };

/** The URL the harness's MemoryNetwork listens on. */
export const MEMORY_URL = 'ws://memory.test/';

/** A scenario source over a fixed list. */
export function scenarioList(defs: readonly ScenarioDefinition[]): ScenarioSource {
  return { get: (n) => defs.find((d) => d.name === n), names: () => defs.map((d) => d.name) };
}

/** Harness options. */
export interface HarnessOptions {
  scenarios: readonly ScenarioDefinition[];
  defaultScenario?: string;
  params?: Record<string, number>;
  snapshotRateHz?: number;
  recordDir?: string | null;
  /** When recorded ticks reach the disk (default: the server's, a sync per tick before its messages leave). */
  durability?: DurabilityOptions;
  latencyMs?: number;
  limits?: Partial<SessionLimits>;
  maxClientsPerRoom?: number;
  maxRooms?: number;
  maxConnections?: number;
  maxPayloadBytes?: number;
  /** Reconnect grace window (ms); default the server's (30 s); 0 turns resume off. */
  resumeGraceMs?: number;
  seats?: SeatTokens | null;
  requireSeat?: boolean;
  /** The server's logger (default: silent). */
  logger?: Logger;
  /** Net mode of the rooms (default: the server's, 'auto'). */
  netMode?: NetModeRequest;
  /** Input delay predict rooms announce (default: the server's, 0). */
  inputDelayTicks?: number;
}

/** A protocol-level client: records every decoded message; decodes and acks snapshots. */
export class TestClient {
  readonly end: MemoryTransport;
  readonly messages: ServerMessage[] = [];
  readonly frames: QuantizedFrame[] = [];
  readonly events: SimEvent[] = [];
  readonly undecodable: string[] = [];
  closed: { code: number; reason: string } | null = null;
  welcome: WelcomeMessage | null = null;
  decoder: SnapshotDecoder | null = null;
  autoAck = true;

  constructor(net: MemoryNetwork, url: string, label: string) {
    this.end = net.connect(url, { open: () => {}, message: (data) => this.receive(data), close: (code, reason) => (this.closed = { code, reason }) }, label);
  }

  private receive(data: Uint8Array): void {
    const r = decodeServerMessage(data);
    if (!r.ok) {
      this.undecodable.push(r.error);
      return;
    }
    const m = r.message;
    this.messages.push(m);
    if (m.type === 'welcome') {
      this.welcome = m;
      this.decoder = new SnapshotDecoder(snapshotFormatFromSpec(m.scenario.bounds, m.snapshotFormat));
    } else if (m.type === 'snapshot') {
      if (!this.decoder) throw new Error('snapshot before welcome');
      const frame = this.decoder.decode(m.bytes).frame;
      this.frames.push(frame);
      if (this.autoAck) this.send({ type: 'ack', tick: frame.tick });
    } else if (m.type === 'events') {
      this.events.push(...m.events);
    }
  }

  /** Sends a typed client message. */
  send(m: Parameters<typeof encodeClientMessage>[0]): void {
    this.end.send(encodeClientMessage(m));
  }

  hello(name: string, room: string | null = null, tokens: { seatToken?: string; resumeToken?: string } = {}): void {
    this.send({ type: 'hello', version: PROTOCOL_VERSION, name, room, ...tokens });
  }

  /** Cuts the link without a bye, as a network failure does (the server sees close code 1006). */
  drop(): void {
    this.end.close(1006, 'link dropped');
  }

  /** Sends commands for consecutive ticks from firstTick. */
  input(firstTick: number, commands: InputCommand[]): void {
    this.send({ type: 'input', firstTick, commands });
  }

  get playerId(): number {
    if (!this.welcome) throw new Error('not welcomed yet');
    return this.welcome.playerId;
  }

  /** Messages of one type. */
  ofType<T extends ServerMessage['type']>(type: T): Extract<ServerMessage, { type: T }>[] {
    return this.messages.filter((m): m is Extract<ServerMessage, { type: T }> => m.type === type);
  }

  latestFrame(): QuantizedFrame {
    const f = this.frames.at(-1);
    if (!f) throw new Error('no snapshot yet');
    return f;
  }
}

/** The running harness. */
export interface Harness {
  clock: ManualClock;
  server: GameServer;
  /** Opens a link to the server and wraps its client end (no hello sent); the server sees it on the next clock run. */
  connect(remote?: string): TestClient;
  /** Connects, says hello and advances until the welcome arrives. */
  join(name: string, room?: string | null): Promise<TestClient>;
  /** Lets pending promises (room creation) settle, advancing the clock 1 ms per turn until `done()` or the limit. */
  settle(done: () => boolean, maxTurns?: number): Promise<void>;
  /** Advances the clock by n tick periods. */
  ticks(n: number): void;
  room(id?: string): Room;
  /** A MemoryNetwork on the harness clock whose MEMORY_URL reaches this server (for sdk's NetClient). */
  network(opts?: MemoryNetworkOptions): MemoryNetwork;
  /** Every record the room stepped, and its hash after each step. */
  history(id?: string): { records: TickInputRecord[]; hashes: string[] };
  close(): Promise<void>;
}

/** Starts a harness server with its default room. */
export async function startHarness(opts: HarnessOptions): Promise<Harness> {
  const clock = new ManualClock();
  const logger = opts.logger ?? silentLogger();
  const server = await GameServer.create({
    factory: createRoomFactory({ scenarios: scenarioList(opts.scenarios), logger, recordDir: opts.recordDir ?? null, durability: opts.durability }),
    defaultScenario: opts.defaultScenario ?? opts.scenarios[0].name,
    defaultParams: opts.params,
    clock,
    logger,
    metrics: createMetrics({ processMetrics: false }),
    snapshotRateHz: opts.snapshotRateHz ?? 30,
    limits: opts.limits,
    maxClientsPerRoom: opts.maxClientsPerRoom,
    maxRooms: opts.maxRooms,
    maxConnections: opts.maxConnections,
    resumeGraceMs: opts.resumeGraceMs,
    seats: opts.seats,
    requireSeat: opts.requireSeat,
    netMode: opts.netMode,
    inputDelayTicks: opts.inputDelayTicks,
  });
  const histories = new Map<string, { records: TickInputRecord[]; hashes: string[] }>();
  const watch = (room: Room): void => {
    if (histories.has(room.id)) return;
    const h = { records: [] as TickInputRecord[], hashes: [] as string[] };
    histories.set(room.id, h);
    room.onTick((record) => {
      h.records.push(structuredClone(record));
      h.hashes.push(room.sim.stateHash());
    });
  };
  for (const r of server.rooms.localRooms()) watch(r);
  let n = 0;
  const links = new MemoryNetwork(clock, { latencyMs: opts.latencyMs ?? 0, maxPayloadBytes: opts.maxPayloadBytes });
  links.listen(MEMORY_URL, (peer) => server.accept(memoryPeerConnection(peer)));
  const h: Harness = {
    clock,
    server,
    connect(remote) {
      return new TestClient(links, MEMORY_URL, remote ?? `test-${++n}`);
    },
    async settle(done, maxTurns = 2000) {
      for (let i = 0; i < maxTurns && !done(); i++) {
        await new Promise((resolve) => setImmediate(resolve));
        clock.advance(1);
      }
    },
    async join(name, room = null) {
      const c = h.connect(name);
      c.hello(name, room);
      await h.settle(() => c.welcome !== null || c.closed !== null);
      if (!c.welcome) throw new Error(`no welcome for ${name}: ${JSON.stringify(c.messages.slice(-2))}`);
      for (const r of server.rooms.localRooms()) watch(r);
      return c;
    },
    ticks(count) {
      clock.advance(count * TICK_MS);
    },
    network(netOpts = {}) {
      const net = new MemoryNetwork(clock, netOpts);
      net.listen(MEMORY_URL, (peer) => server.accept(memoryPeerConnection(peer)));
      return net;
    },
    room(id = 'default') {
      const r = server.rooms.local(id);
      if (!r) throw new Error(`no room ${id}`);
      return r;
    },
    history(id = 'default') {
      const got = histories.get(id);
      if (!got) throw new Error(`no history for room ${id}`);
      return got;
    },
    close: () => server.close('test over'),
  };
  return h;
}
