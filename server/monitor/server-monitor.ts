// The operators' view of a running server: every open room (scenario, net mode, ticks/s, tick p50/p99, players,
// bodies, WASM heap, bandwidth) with its players (name, RTT, input lead, late inputs, kbps), sampled once a second on
// the server's clock, pushed to subscribers (the SSE route) and exported as per-room Prometheus gauges. Actions: close a room, kick
// a player. Reads rooms and sessions through their public surface; never steps or changes a simulation itself.
import { Gauge } from 'prom-client';
import type { Clock, TimerHandle } from '../../shared/clock.ts';
import { ByeReason } from '../../shared/protocol/opcodes.ts';
import { CloseCode } from '../connection.ts';
import type { GameServer } from '../game-server.ts';
import { HttpError, HttpErrorCode } from '../http-errors.ts';
import { DEFAULT_ROOM_ID } from '../room-manager.ts';
import { Room } from '../room.ts';
import { RemoteRoom } from '../workers/remote-room.ts';
import { RateMeter } from './rate-meter.ts';

/** How often the monitor samples (ms). */
export const MONITOR_SAMPLE_MS = 1000;

/** One player as the monitor shows it. */
export interface MonitorPlayer {
  playerId: number;
  name: string;
  /** Snapshot → ack round trip (ms), null before the first ack. */
  rttMs: number | null;
  /** How far ahead of the room's tick its newest input arrived (ticks), null before the first input. */
  inputLeadTicks: number | null;
  /** Inputs that arrived after their tick was simulated. */
  lateInputs: number;
  /** Ticks simulated with its previous input repeated because none had arrived. */
  missedInputTicks: number;
  kbpsIn: number;
  kbpsOut: number;
}

/** One room as the monitor shows it. */
export interface MonitorRoom {
  id: string;
  scenario: string;
  params: Readonly<Record<string, number>>;
  tick: number;
  ticksPerSecond: number;
  /** Wall time of the last 240 ticks (ms); null before the first tick, and for a room in a worker thread. */
  tickMs: { p50: number; p99: number } | null;
  /** Mean CPU per tick (ms) a worker thread reports for its room; null for rooms on the main thread. */
  tickCpuMeanMs: number | null;
  /** The worker thread running the room (serve --room-workers), or null on the main thread. */
  worker: number | null;
  /** How the room serves its players: snapshots, or input records for predicting clients. */
  netMode: string;
  snapshotRateHz: number;
  /** Players in the room, counting those held for a reconnect. */
  playerCount: number;
  /** Players whose link is down (held for a reconnect). */
  heldCount: number;
  bodies: number;
  wasmHeap: { usedBytes: number; freeBytes: number } | null;
  kbpsIn: number;
  kbpsOut: number;
  players: MonitorPlayer[];
  /** Whether the close action applies (the default room stays open while the server runs). */
  closable: boolean;
}

/** The whole picture, as JSON and as each SSE event. */
export interface MonitorState {
  /** The server clock when sampled (ms). */
  sampledAtMs: number;
  rooms: MonitorRoom[];
}

const kbps = (bytesPerSecond: number): number => Math.round((bytesPerSecond * 8) / 100) / 10;
const round2 = (v: number): number => Math.round(v * 100) / 100;

/** Samples a GameServer for operators; close() stops the sampler. */
export class ServerMonitor {
  private readonly game: GameServer;
  private readonly clock: Clock;
  private readonly meters = new Map<string, RateMeter>();
  private readonly subscribers = new Set<(state: MonitorState) => void>();
  private timer: TimerHandle | null = null;
  private latest: MonitorState;
  private closed = false;

  constructor(game: GameServer) {
    this.game = game;
    this.clock = game.clock;
    this.latest = this.sample();
    this.registerGauges();
    this.schedule();
  }

  /** The latest sample (taken at most MONITOR_SAMPLE_MS ago). */
  state(): MonitorState {
    return this.latest;
  }

  /** Calls `fn` with every new sample (and once now); returns the unsubscribe function. */
  subscribe(fn: (state: MonitorState) => void): () => void {
    this.subscribers.add(fn);
    fn(this.latest);
    return () => this.subscribers.delete(fn);
  }

  /** Closes a room: its players get a `room-closed` bye. Throws an HttpError for the default room or an unknown id. */
  async closeRoom(roomId: string): Promise<void> {
    if (roomId === DEFAULT_ROOM_ID) throw new HttpError(409, HttpErrorCode.DefaultRoom, 'the default room stays open while the server runs');
    const room = this.game.rooms.get(roomId);
    if (!room) throw new HttpError(404, HttpErrorCode.RoomNotFound, `no room ${JSON.stringify(roomId.slice(0, 64))}`);
    this.game.logger.info({ room: roomId, clients: room.clientCount }, 'room closed from the monitor');
    await room.close(`room ${roomId} was closed by an operator`);
    this.refresh();
  }

  /** Removes a player: a `kicked` bye, and the player leaves the room. Throws an HttpError when it is not connected. */
  kickPlayer(roomId: string, playerId: number): void {
    const session = this.game.sessionList().find((s) => !s.ended && s.currentRoom?.id === roomId && s.player === playerId);
    if (!session) throw new HttpError(404, HttpErrorCode.NotFound, `no connected player ${playerId} in room ${JSON.stringify(roomId.slice(0, 64))}`);
    this.game.logger.info({ room: roomId, playerId }, 'player kicked from the monitor');
    session.end(ByeReason.Kicked, 'an operator removed you from the room', CloseCode.Normal);
    this.refresh();
  }

  /** Stops sampling and drops the subscribers. Idempotent. */
  close(): void {
    this.closed = true;
    if (this.timer) this.clock.clearTimer(this.timer);
    this.timer = null;
    this.subscribers.clear();
  }

  private schedule(): void {
    if (this.closed) return;
    this.timer = this.clock.setTimer(MONITOR_SAMPLE_MS, () => {
      this.timer = null;
      this.refresh();
      this.schedule();
    });
  }

  // Takes a sample now and pushes it (after an action, so pages see its effect without waiting for the next second).
  private refresh(): void {
    if (this.closed) return;
    this.latest = this.sample();
    for (const fn of [...this.subscribers]) fn(this.latest);
  }

  private meter(key: string, nowMs: number, cumulative: number, seen: Set<string>): number {
    seen.add(key);
    let m = this.meters.get(key);
    if (!m) this.meters.set(key, (m = new RateMeter()));
    m.sample(nowMs, cumulative);
    return m.perSecond();
  }

  private sample(): MonitorState {
    const nowMs = this.clock.nowMs();
    const seen = new Set<string>();
    const sessions = this.game.sessionList();
    const rooms = [...this.game.rooms.all()].sort((a, b) => a.id.localeCompare(b.id));
    const out: MonitorRoom[] = rooms.map((room) => {
      const players: MonitorPlayer[] = [];
      for (const s of sessions) {
        if (s.ended || s.currentRoom !== room) continue;
        const key = `s${s.id}`;
        players.push({
          playerId: s.player,
          name: s.link.name,
          rttMs: s.link.rttMs === null ? null : round2(s.link.rttMs),
          inputLeadTicks: s.link.inputLeadTicks,
          lateInputs: s.stats.inputsLate,
          missedInputTicks: s.missedInputTicks(),
          kbpsIn: kbps(this.meter(`${key}:in`, nowMs, s.link.bytesIn, seen)),
          kbpsOut: kbps(this.meter(`${key}:out`, nowMs, s.stats.bytesSent, seen)),
        });
      }
      players.sort((a, b) => a.playerId - b.playerId);
      // A room on this thread keeps its tick times; one in a worker reports its mean CPU per tick.
      const local = room instanceof Room ? room : null;
      const remote = room instanceof RemoteRoom ? room : null;
      const p = local ? local.tickTimes.percentiles() : null;
      const info = room.info();
      const connected = players.length;
      return {
        id: room.id,
        scenario: room.scenarioName,
        params: room.params,
        worker: remote ? remote.workerIndex : null,
        netMode: info.netMode,
        tick: info.tick,
        ticksPerSecond: round2(this.meter(`r${room.id}:ticks`, nowMs, info.tick, seen)),
        tickMs: p ? { p50: round2(p.p50Ms), p99: round2(p.p99Ms) } : null,
        tickCpuMeanMs: remote?.status?.tickCpuMs ?? null,
        snapshotRateHz: this.game.snapshotRateHz,
        playerCount: room.clientCount,
        heldCount: local ? local.heldCount : Math.max(0, room.clientCount - connected),
        bodies: info.bodies,
        wasmHeap: room.heapUsage(),
        kbpsIn: round2(players.reduce((a, x) => a + x.kbpsIn, 0)),
        kbpsOut: round2(players.reduce((a, x) => a + x.kbpsOut, 0)),
        players,
        closable: room.id !== DEFAULT_ROOM_ID,
      };
    });
    for (const key of [...this.meters.keys()]) if (!seen.has(key)) this.meters.delete(key);
    return { sampledAtMs: nowMs, rooms: out };
  }

  // Per-room gauges on the server's registry, read from the latest sample at scrape time: only open rooms are
  // labelled, so the label count is bounded by the room cap (--max-rooms).
  private registerGauges(): void {
    const registers = [this.game.metrics.registry];
    const rows = (): MonitorRoom[] => this.latest.rooms;
    const perRoom = (name: string, help: string, value: (r: MonitorRoom) => number | null, labelNames: string[] = ['room', 'scenario']): void => {
      new Gauge({
        name,
        help,
        labelNames,
        registers,
        collect() {
          this.reset();
          for (const r of rows()) {
            const v = value(r);
            if (v !== null) this.set({ room: r.id, scenario: r.scenario }, v);
          }
        },
      });
    };
    perRoom('taos_room_players', 'Players in each open room (held ones included)', (r) => r.playerCount);
    perRoom('taos_room_bodies', 'Bodies in each open room', (r) => r.bodies);
    perRoom('taos_room_tick_p50_seconds', "Median wall time of each open room's last 240 ticks", (r) => (r.tickMs ? r.tickMs.p50 / 1000 : null));
    perRoom('taos_room_tick_p99_seconds', "99th percentile wall time of each open room's last 240 ticks", (r) => (r.tickMs ? r.tickMs.p99 / 1000 : null));
    perRoom('taos_room_kbps_in', 'Kilobits per second received from the players of each open room', (r) => r.kbpsIn);
    perRoom('taos_room_kbps_out', 'Kilobits per second sent to the players of each open room', (r) => r.kbpsOut);
  }
}
