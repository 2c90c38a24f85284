// The transport-agnostic server core: rooms, client sessions, metrics and logs on one clock. It accepts
// ServerConnections from any transport (the ws gateway, or in-memory links in tests) and shuts everything down cleanly.
import type { Clock } from '../shared/clock.ts';
import { ByeReason, encodeServerMessage, MAX_INPUT_DELAY_TICKS } from '../shared/protocol/index.ts';
import { TICK_RATE_HZ } from '../shared/tick-rate.ts';
import type { SessionAccess } from './access/admission.ts';
import { DEFAULT_RESUME_GRACE_MS, ResumeTokens } from './access/resume-tokens.ts';
import type { SeatTokens } from './access/seat-tokens.ts';
import { CatchUpBudget } from './catch-up-budget.ts';
import { TickPhases } from './tick-phases.ts';
import { SystemClock } from './clock.ts';
import { ClientSession } from './client-session.ts';
import { DEFAULT_SESSION_LIMITS, type SessionLimits } from './session-context.ts';
import { CloseCode, type ServerConnection } from './connection.ts';
import { createLogger, type Logger } from './logger.ts';
import { createMetrics, renderMergedMetrics, type ServerMetrics } from './metrics.ts';
import type { NetModeRequest } from './net-mode-policy.ts';
import type { RoomInfo } from './room.ts';
import type { HostedRoom } from './hosted-room.ts';
import { RoomManager, type RoomDirectory, type RoomFactory } from './room-manager.ts';
import type { WorkerPool } from './workers/worker-pool.ts';

/** Options of GameServer.create. */
export interface GameServerOptions {
  factory: RoomFactory;
  /** Scenario of the default room. */
  defaultScenario: string;
  defaultParams?: Readonly<Record<string, number>>;
  seed?: number | string;
  clock?: Clock;
  metrics?: ServerMetrics;
  logger?: Logger;
  /** Snapshots per second per client (1–60). Default 30. */
  snapshotRateHz?: number;
  /** Most clients per room. Default 32. */
  maxClientsPerRoom?: number;
  /** Most connections to the whole process. Default 256. */
  maxConnections?: number;
  maxRooms?: number;
  emptyRoomGraceMs?: number;
  maxCatchUpTicks?: number;
  maxInputLeadTicks?: number;
  pauseWhenEmpty?: boolean;
  /** Net mode of rooms not asked for one ('auto': predict where the cost estimate allows). Default 'auto'. */
  netMode?: NetModeRequest;
  /** Input delay (ticks, 0..MAX_INPUT_DELAY_TICKS) the welcome of a predict room announces. Default 0. */
  inputDelayTicks?: number;
  limits?: Partial<SessionLimits>;
  /** How long a player whose link dropped is held for a reconnect with its resume token (ms). Default 30 000; 0: off. */
  resumeGraceMs?: number;
  /** Seat tokens this server issues and accepts (POST /api/rooms/:id/seats). Default none. */
  seats?: SeatTokens | null;
  /** Refuse hellos without a valid seat token. Needs `seats`. Default false. */
  requireSeat?: boolean;
  /** Room workers to run the rooms in (the server stops them when it closes). Default none: rooms on this thread. */
  workers?: WorkerPool | null;
  /** Runs before the default room opens (serve --resume reopens crashed rooms here, the default one included). */
  beforeDefaultRoom?: (server: GameServer) => Promise<void>;
  /** Hears every resume token issued, by key (recordings keep them for --resume). */
  onResumeTokenIssued?: (room: HostedRoom, playerId: number, key: string) => void;
  /** With a fleet (`--redis`): room ids are claimed fleet-wide here (server/fleet/). */
  directory?: RoomDirectory;
}

/** The server core. */
export class GameServer {
  readonly clock: Clock;
  readonly metrics: ServerMetrics;
  readonly logger: Logger;
  readonly rooms: RoomManager;
  readonly limits: SessionLimits;
  readonly snapshotRateHz: number;
  /** Input delay (ticks) predict rooms announce. */
  readonly inputDelayTicks: number;
  readonly maxConnections: number;
  /** Seat and resume rules every session applies. */
  readonly access: SessionAccess;
  /** The room workers, or null when rooms run on this thread. */
  readonly workers: WorkerPool | null;
  private readonly sessions = new Set<ClientSession>();
  private readonly startedMs: number;
  private closing: Promise<void> | null = null;

  private constructor(opts: GameServerOptions) {
    this.clock = opts.clock ?? new SystemClock();
    this.metrics = opts.metrics ?? createMetrics();
    this.logger = opts.logger ?? createLogger();
    this.limits = { ...DEFAULT_SESSION_LIMITS, ...opts.limits };
    this.snapshotRateHz = opts.snapshotRateHz ?? 30;
    if (!(this.snapshotRateHz >= 1 && this.snapshotRateHz <= TICK_RATE_HZ)) throw new Error(`snapshot rate must be in [1, ${TICK_RATE_HZ}] Hz, got ${this.snapshotRateHz}`);
    this.inputDelayTicks = opts.inputDelayTicks ?? 0;
    if (!(Number.isInteger(this.inputDelayTicks) && this.inputDelayTicks >= 0 && this.inputDelayTicks <= MAX_INPUT_DELAY_TICKS)) {
      throw new Error(`input delay must be an integer in [0, ${MAX_INPUT_DELAY_TICKS}] ticks, got ${this.inputDelayTicks}`);
    }
    this.maxConnections = opts.maxConnections ?? 256;
    this.startedMs = this.clock.nowMs();
    this.workers = opts.workers ?? null;
    this.workers?.registerMetrics(this.metrics.registry);
    const graceMs = opts.resumeGraceMs ?? DEFAULT_RESUME_GRACE_MS;
    const seats = opts.seats ?? null;
    if (opts.requireSeat === true && seats === null) throw new Error('requireSeat needs seat tokens (a join secret) to check');
    this.access = {
      resume: graceMs > 0 ? new ResumeTokens({ clock: this.clock, graceMs, logger: this.logger, onIssue: opts.onResumeTokenIssued }) : null,
      seats,
      requireSeat: opts.requireSeat ?? false,
    };
    this.rooms = new RoomManager({
      clock: this.clock,
      metrics: this.metrics,
      logger: this.logger,
      factory: opts.factory,
      defaultScenario: opts.defaultScenario,
      defaultParams: opts.defaultParams,
      seed: opts.seed,
      snapshotRateHz: this.snapshotRateHz,
      maxClientsPerRoom: opts.maxClientsPerRoom ?? 32,
      maxRooms: opts.maxRooms,
      emptyRoomGraceMs: opts.emptyRoomGraceMs,
      maxCatchUpTicks: opts.maxCatchUpTicks,
      maxInputLeadTicks: opts.maxInputLeadTicks,
      pauseWhenEmpty: opts.pauseWhenEmpty,
      netMode: opts.netMode,
      host: this.workers,
      // Rooms on this thread share its loop: on the real clock, a late room may not run its catch-up ticks back to back.
      catchUp: this.clock instanceof SystemClock ? new CatchUpBudget() : null,
      phases: this.clock instanceof SystemClock ? new TickPhases() : null,
      directory: opts.directory,
    });
    this.metrics.setRoomHeapSource(() => this.roomHeaps());
    this.metrics.setRoomPaceSource(() => this.rooms.list().map((r) => ({ room: r.id, slow: r.slow })));
  }

  /** Each open room's WASM heap (rooms whose simulation does not report one are left out). */
  roomHeaps(): Array<{ room: string; usedBytes: number; freeBytes: number }> {
    const out: Array<{ room: string; usedBytes: number; freeBytes: number }> = [];
    for (const room of this.rooms.all()) {
      const heap = room.heapUsage();
      if (heap) out.push({ room: room.id, ...heap });
    }
    return out;
  }

  /** Builds the server and opens its default room (throws a clear Error for a bad scenario or parameters). */
  static async create(opts: GameServerOptions): Promise<GameServer> {
    const server = new GameServer(opts);
    await opts.beforeDefaultRoom?.(server);
    try {
      await server.rooms.start();
    } catch (error) {
      await server.workers?.stop();
      throw new Error(`cannot open the default room (scenario ${opts.defaultScenario}): ${error instanceof Error ? error.message : String(error)}`, { cause: error });
    }
    return server;
  }

  /** The open sessions (a copy), for the monitor. */
  sessionList(): ClientSession[] {
    return [...this.sessions];
  }

  /** The Prometheus exposition of this thread's metrics summed with every room worker's. */
  async renderMetrics(): Promise<{ body: string; contentType: string }> {
    return renderMergedMetrics(this.metrics, this.workers ? await this.workers.metricsJson() : []);
  }

  /** Open sessions. */
  sessionCount(): number {
    return this.sessions.size;
  }

  /** Whether the server is shutting down (new connections are refused). */
  get isClosing(): boolean {
    return this.closing !== null;
  }

  /** A reason to refuse a new connection now, or null. */
  refusal(): string | null {
    if (this.closing) return 'server shutting down';
    if (this.sessions.size >= this.maxConnections) return `server full (${this.maxConnections} connections)`;
    return null;
  }

  /** Takes a new client link: a session when accepted; otherwise the link gets a bye and is closed. */
  accept(conn: ServerConnection): ClientSession | null {
    const refusal = this.refusal();
    if (refusal !== null) {
      const reason = this.closing ? ByeReason.ServerShutdown : ByeReason.ServerFull;
      conn.attach({ message: () => {}, close: () => {} });
      conn.send(encodeServerMessage({ type: 'bye', reason, message: refusal }));
      conn.close(CloseCode.TryAgainLater, `${reason}: ${refusal}`);
      this.metrics.disconnects.inc({ reason });
      return null;
    }
    const session = new ClientSession(conn, {
      clock: this.clock,
      metrics: this.metrics,
      logger: this.logger,
      rooms: this.rooms,
      limits: this.limits,
      access: this.access,
      inputDelayTicks: this.inputDelayTicks,
      onEnd: (s) => this.sessions.delete(s),
    });
    if (!session.ended) this.sessions.add(session);
    return session;
  }

  /** Rooms for GET /api/rooms. */
  listRooms(): RoomInfo[] {
    return this.rooms.list();
  }

  /** The /healthz answer. */
  health(): { ok: boolean; status: string; uptimeSeconds: number; rooms: number; clients: number } {
    return {
      ok: this.closing === null,
      status: this.closing === null ? 'ok' : 'shutting down',
      uptimeSeconds: Math.round((this.clock.nowMs() - this.startedMs) / 1000),
      rooms: this.rooms.all().length,
      clients: this.sessions.size,
    };
  }

  /** Tells every client why (bye), closes every room (recordings get their end record) and refuses new work. */
  close(reason: string): Promise<void> {
    if (this.closing) return this.closing;
    this.closing = (async () => {
      this.logger.info({ reason, sessions: this.sessions.size }, 'closing the server');
      for (const s of [...this.sessions]) s.end(ByeReason.ServerShutdown, reason, CloseCode.GoingAway);
      await this.rooms.closeAll(reason);
      await this.workers?.stop();
    })();
    return this.closing;
  }
}
