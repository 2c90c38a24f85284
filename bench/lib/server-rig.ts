// An in-process server for the tick-overhead figure: the real GameServer, room, client sessions, snapshot encoders and
// input-log writer, driven tick by tick. Clients sit behind tick-scheduled links and send what the real client sends
// (input messages from its InputSender with redundancy carrying snapshot acks, pings); the server's part of a tick (handling the
// arrived messages + Room.tickOnce) is what `serverTick()` runs, and the clients' part (`clientTick()`) runs outside it.
import '../../server/physics-node.ts';
import { mkdtemp, rm } from 'node:fs/promises';
import { tmpdir } from 'node:os';
import { join } from 'node:path';
import { getScenario } from '../../scenarios/index.ts';
import type { ClientSession } from '../../server/client-session.ts';
import type { Clock, TimerHandle } from '../../shared/clock.ts';
import type { ConnectionHandlers, ServerConnection } from '../../server/connection.ts';
import { GameServer } from '../../server/game-server.ts';
import { installedJoltVersion, LogWriter } from '../../server/log/index.ts';
import { silentLogger } from '../../server/logger.ts';
import { DeliveringMember } from '../../server/member-delivery.ts';
import { createMetrics } from '../../server/metrics.ts';
import type { Room, RoomRecorder } from '../../server/room.ts';
import type { RoomFactory, RoomSimulationBuild } from '../../server/room-manager.ts';
import { CharacterController } from '../../shared/physics/index.ts';
import { decodeServerMessage, DEFAULT_INPUT_REDUNDANCY, encodeClientMessage, PROTOCOL_VERSION, readSnapshotHeader } from '../../shared/protocol/index.ts';
import { BotScript } from '../../shared/sim/bots.ts';
import { Simulation } from '../../shared/sim/simulation.ts';
import { AckCarrier, InputSender } from './client-lib.ts';
import { wsFrameBytes } from './wire.ts';
import { TICK_MS, TICK_RATE_HZ } from '../../shared/tick-rate.ts';

/** The client library's steady ping interval (its initial burst of quick pings happens during the join, unmeasured). */
const PING_INTERVAL_MS = 1000;

/**
 * Time for the server's rate limiters, advanced by the rig one tick at a time. Its timers never fire: the rig runs
 * every tick itself (Room.tickOnce), so the room's own tick loop, started when the first player joins, stays idle.
 */
class RigClock implements Clock {
  private now = 0;
  private nextId = 1;
  nowMs(): number {
    return this.now;
  }
  setTimer(): TimerHandle {
    return { id: this.nextId++ };
  }
  clearTimer(): void {}
  advance(ms: number): void {
    this.now += ms;
  }
}

/** A server⇄client link whose client→server messages are due at a tick; server→client messages wait in an outbox. */
class RigLink implements ServerConnection {
  readonly remote: string;
  private handlers: ConnectionHandlers | null = null;
  private early: Uint8Array[] = [];
  private open = true;
  readonly outbox: Uint8Array[] = [];
  constructor(remote: string) {
    this.remote = remote;
  }
  send(data: Uint8Array): void {
    if (this.open) this.outbox.push(data);
  }
  bufferedAmount(): number {
    return 0;
  }
  isOpen(): boolean {
    return this.open;
  }
  close(): void {
    this.open = false;
  }
  attach(handlers: ConnectionHandlers): void {
    this.handlers = handlers;
    for (const d of this.early.splice(0)) handlers.message(d, true);
  }
  /** Hands one client message to the server (as the socket would). */
  deliver(data: Uint8Array): void {
    if (!this.open) return;
    if (this.handlers) this.handlers.message(data, true);
    else this.early.push(data);
  }
}

interface RigClient {
  link: RigLink;
  session: ClientSession;
  playerId: number;
  /** The client library's own input sender: one message per tick carrying the newest commands (redundancy 4). */
  sender: InputSender;
  /** Acks of snapshots the client has decoded, for its next input message (the library's AckCarrier). */
  acks: AckCarrier;
  /** Snapshot ticks by the client tick they reach the client at (one way after they were sent). */
  arriving: Map<number, number[]>;
  nextPingMs: number;
  /** Client→server messages by the tick they arrive at. */
  inbound: Map<number, Uint8Array[]>;
  bytesDown: number;
  snapshots: number;
  /** The newest snapshot tick received (completes the next delta snapshot's tick). */
  snapshotTick: number | null;
  /** Size on the wire of the welcome the server sent (WebSocket framing included). */
  welcomeBytes: number;
}

/** Rig options. */
export interface ServerRigOptions {
  scenario: string;
  params: Readonly<Record<string, number>>;
  /** Checkpoint bytes the room's simulation starts from (a warmed-up scene); null: tick 0. */
  startBytes: Uint8Array | null;
  clients: number;
  snapshotRateHz: number;
  /** One-way client⇄server delay in ticks (acks arrive 2× this after their snapshot was sent). */
  oneWayTicks: number;
  /** A hash record in the room's input log every N ticks. */
  hashEveryTicks: number;
}

/** Where the server's time goes inside serverTick(), summed since the last reset (ms). */
export interface TickParts {
  messagesIn: number;
  simStep: number;
  /** Character updates (CharacterController.move) inside simStep. */
  characters: number;
  physicsStep: number;
  stateHash: number;
  snapshots: number;
  events: number;
}

/** The running rig. */
export interface ServerRig {
  sim: Simulation;
  room: Room;
  /** The server's share of one tick: arrived client messages, then Room.tickOnce(). */
  serverTick(): void;
  /** The clients' share: read what the server sent, ack snapshots, send the next inputs. Lets the log writer run. */
  clientTick(): Promise<void>;
  /** Parts of serverTick() since the last takeParts(). */
  takeParts(): TickParts;
  /** Bytes sent to each client (mean, WebSocket framing included) and snapshots received, since the start. */
  downstream(): { bytesPerClient: number; snapshotsPerClient: number };
  /** Size on the wire of the first client's welcome. */
  welcomeBytes(): number;
  close(): Promise<void>;
}

function zeroParts(): TickParts {
  return { messagesIn: 0, simStep: 0, characters: 0, physicsStep: 0, stateHash: 0, snapshots: 0, events: 0 };
}

/** Wraps obj[name] so its time is added to parts[key]. Measurement only: arguments and results pass through. */
function timeMethod<T extends object>(obj: T, name: keyof T & string, parts: { current: TickParts }, key: keyof TickParts): void {
  const original = (obj[name] as (...args: unknown[]) => unknown).bind(obj);
  (obj as Record<string, unknown>)[name] = (...args: unknown[]): unknown => {
    const t0 = performance.now();
    try {
      return original(...args);
    } finally {
      parts.current[key] += performance.now() - t0;
    }
  };
}

/** Times every CharacterController.move() into parts[key] (the rig's characters are made inside Simulation.step). */
function timeCharacterMoves(parts: { current: TickParts }): () => void {
  const proto = CharacterController.prototype;
  const original = proto.move;
  proto.move = function timedMove(this: CharacterController, dtSeconds: number): void {
    const t0 = performance.now();
    try {
      original.call(this, dtSeconds);
    } finally {
      parts.current.characters += performance.now() - t0;
    }
  };
  return () => {
    proto.move = original;
  };
}

/** Times every DeliveringMember's frame and event deliveries (encoding and the hand-off to the session's socket). */
function timeDeliveries(parts: { current: TickParts }): () => void {
  const proto = DeliveringMember.prototype;
  const { deliverFrame, deliverEvents } = proto;
  proto.deliverFrame = function timedFrame(this: DeliveringMember, ...args: Parameters<typeof deliverFrame>): void {
    const t0 = performance.now();
    try {
      deliverFrame.apply(this, args);
    } finally {
      parts.current.snapshots += performance.now() - t0;
    }
  };
  proto.deliverEvents = function timedEvents(this: DeliveringMember, ...args: Parameters<typeof deliverEvents>): void {
    const t0 = performance.now();
    try {
      deliverEvents.apply(this, args);
    } finally {
      parts.current.events += performance.now() - t0;
    }
  };
  return () => {
    proto.deliverFrame = deliverFrame;
    proto.deliverEvents = deliverEvents;
  };
}

/**
 * A recorder like the server's --record one: every tick record and a hash every N ticks. A log starts at tick 0, and
 * the rig's room may start from a warmed-up checkpoint, so ticks are written relative to `startTick` (same bytes
 * and cost; the file is scratch and never replayed).
 */
async function createRigRecorder(dir: string, scenario: string, params: Readonly<Record<string, number>>, hashEveryTicks: number, startTick: number): Promise<RoomRecorder> {
  const writer = await LogWriter.create(join(dir, 'room.taoslog'), {
    joltVersion: installedJoltVersion(),
    scenario,
    params: { ...params },
    seed: 1,
    tickRateHz: TICK_RATE_HZ,
    hashEveryTicks,
    checkpointEveryTicks: 0,
    createdBy: 'bench tick-overhead',
  });
  return {
    append: (record) => writer.appendTick({ ...record, tick: record.tick - startTick }),
    afterStep: (tick, hash) => {
      if ((tick - startTick) % hashEveryTicks === 0) writer.appendHash(tick - startTick, hash());
    },
    close: () => writer.abandon(),
  };
}

/** Starts the server with its default room on the scene and joins `clients` players, each driven by a scripted bot. */
export async function startServerRig(opts: ServerRigOptions): Promise<ServerRig> {
  const clock = new RigClock();
  const logDir = await mkdtemp(join(tmpdir(), 'taos-bench-rig-'));
  const parts = { current: zeroParts() };
  let sim: Simulation | null = null;
  const factory: RoomFactory = {
    hasScenario: (name) => name === opts.scenario,
    async createSimulation(name, params, seed): Promise<RoomSimulationBuild> {
      const def = getScenario(name);
      const s = await Simulation.create({ scenario: def, params, seed });
      if (opts.startBytes) s.restoreCheckpointBytes(opts.startBytes);
      sim = s;
      return { sim: s, maxBodies: s.world.maxBodies, params: { ...s.params }, description: def.description, bounds: def.bounds };
    },
    createRecorder: (room) => createRigRecorder(logDir, opts.scenario, opts.params, opts.hashEveryTicks, room.sim.tick),
  };
  const server = await GameServer.create({
    factory,
    defaultScenario: opts.scenario,
    defaultParams: opts.params,
    clock,
    logger: silentLogger(),
    metrics: createMetrics({ processMetrics: false }),
    snapshotRateHz: opts.snapshotRateHz,
    maxClientsPerRoom: Math.max(32, opts.clients),
    maxConnections: Math.max(256, opts.clients),
  });
  const room = server.rooms.localRooms()[0];
  const theSim = sim as Simulation | null;
  if (!theSim || !room) throw new Error('server rig: the default room did not open');
  timeMethod(theSim, 'step', parts, 'simStep');
  timeMethod(theSim.world, 'stepFixed', parts, 'physicsStep');
  timeMethod(theSim, 'stateHash', parts, 'stateHash');
  const untimeCharacters = timeCharacterMoves(parts);
  const untimeDeliveries = timeDeliveries(parts);

  const clients: RigClient[] = [];
  for (let i = 0; i < opts.clients; i++) {
    const link = new RigLink(`bench-${i + 1}`);
    const session = server.accept(link);
    if (!session) throw new Error(`server rig: client ${i + 1} was refused`);
    link.deliver(encodeClientMessage({ type: 'hello', version: PROTOCOL_VERSION, name: `bot-${i + 1}`, room: null }));
    for (let turn = 0; session.player === 0 && turn < 1000; turn++) await new Promise((r) => setImmediate(r));
    if (session.player === 0) throw new Error(`server rig: client ${i + 1} was not welcomed`);
    const welcome = link.outbox.length > 0 ? decodeServerMessage(link.outbox[0]) : null;
    if (!welcome?.ok || welcome.message.type !== 'welcome') throw new Error(`server rig: client ${i + 1} got no welcome first`);
    clients.push({
      link,
      session,
      playerId: session.player,
      sender: new InputSender({ redundancy: DEFAULT_INPUT_REDUNDANCY }),
      acks: new AckCarrier(),
      arriving: new Map(),
      // Steady pings spread over the second, as clients that joined at different times would be.
      nextPingMs: clock.nowMs() + (i * PING_INTERVAL_MS) / opts.clients,
      inbound: new Map(),
      bytesDown: 0,
      snapshots: 0,
      snapshotTick: null,
      welcomeBytes: wsFrameBytes(link.outbox[0].length),
    });
  }
  room.tickClock.stop();
  // Bots with the same player ids the room gave out (1…N in join order); their join records are the room's business.
  const bots = new BotScript({ seed: 1, bots: opts.clients, firstPlayerId: clients[0]?.playerId ?? 1, joinTicks: clients.map(() => 0) });
  const lead = opts.oneWayTicks + 1;
  const queue = (c: RigClient, atTick: number, data: Uint8Array): void => {
    const list = c.inbound.get(atTick);
    if (list) list.push(data);
    else c.inbound.set(atTick, [data]);
  };

  return {
    sim: theSim,
    room,
    serverTick(): void {
      const tick = theSim.tick;
      const t0 = performance.now();
      for (const c of clients) {
        const due = c.inbound.get(tick);
        if (!due) continue;
        c.inbound.delete(tick);
        for (const d of due) c.link.deliver(d);
      }
      parts.current.messagesIn += performance.now() - t0;
      room.tickOnce();
    },
    async clientTick(): Promise<void> {
      const now = theSim.tick; // the tick the server runs next
      clock.advance(TICK_MS);
      const nowMs = clock.nowMs();
      const record = bots.next();
      const byPlayer = new Map(record.commands.map((c) => [c.playerId, c.input]));
      for (const c of clients) {
        for (const bytes of c.link.outbox.splice(0)) {
          c.bytesDown += wsFrameBytes(bytes.length);
          const m = decodeServerMessage(bytes);
          if (!m.ok) throw new Error(`server rig: undecodable server message: ${m.error}`);
          if (m.message.type === 'snapshot') {
            c.snapshots++;
            // The snapshot reaches the client after one way; its ack rides on the first input message sent after that.
            const tick = readSnapshotHeader(m.message.bytes, c.snapshotTick).tick;
            c.snapshotTick = tick;
            const at = now - 1 + opts.oneWayTicks;
            const list = c.arriving.get(at);
            if (list) list.push(tick);
            else c.arriving.set(at, [tick]);
          } else if (m.message.type === 'bye') throw new Error(`server rig: client ${c.playerId} was sent away: ${m.message.message}`);
        }
        for (const [at, ticks] of c.arriving) {
          if (at > now) continue;
          for (const tick of ticks) c.acks.decoded(tick);
          c.arriving.delete(at);
        }
        const input = byPlayer.get(c.playerId);
        if (input) c.sender.setCommand(input);
        const message = input ? c.sender.update(now + lead) : null;
        if (message) {
          const ackTick = c.acks.carry();
          if (ackTick !== undefined) message.ackTick = ackTick;
          queue(c, now + opts.oneWayTicks, encodeClientMessage(message));
        } else {
          const ackTick = c.acks.alone();
          if (ackTick !== null) queue(c, now + opts.oneWayTicks, encodeClientMessage({ type: 'ack', tick: ackTick }));
        }
        if (nowMs >= c.nextPingMs) {
          queue(c, now + opts.oneWayTicks, encodeClientMessage({ type: 'ping', clientTimeMs: nowMs }));
          c.nextPingMs += PING_INTERVAL_MS;
        }
      }
      await new Promise((r) => setImmediate(r));
    },
    takeParts(): TickParts {
      const p = parts.current;
      parts.current = zeroParts();
      return p;
    },
    downstream() {
      const n = Math.max(1, clients.length);
      return { bytesPerClient: clients.reduce((s, c) => s + c.bytesDown, 0) / n, snapshotsPerClient: clients.reduce((s, c) => s + c.snapshots, 0) / n };
    },
    welcomeBytes: () => clients[0]?.welcomeBytes ?? 0,
    async close(): Promise<void> {
      untimeCharacters();
      untimeDeliveries();
      await server.close('bench done');
      await rm(logDir, { recursive: true, force: true });
    },
  };
}
