// The room workers of a server (serve --room-workers N): starts them, places each new room on the worker with the most
// headroom by measured (or estimated) CPU per tick, refuses a room no worker has room for (503 with the reason), and
// replaces a worker that died. The RoomManager opens rooms through it instead of on the main thread.
import { Counter, Gauge, Histogram, type Registry } from 'prom-client';
import { ErrorCode } from '../../shared/protocol/opcodes.ts';
import type { Logger } from '../logger.ts';
import { RoomError } from '../room.ts';
import type { RoomHost, RoomSpec } from '../room-manager.ts';
import type { RemoteRoom, RoomMoveSummary } from './remote-room.ts';
import { planMove, type MovePlan, type PolicyWorker } from './move-policy.ts';
import { estimateTickCpuMs, placeRoom, roomTickCpuMs, WORKER_BUDGET_MS_PER_TICK } from './room-cost.ts';
import { RoomThread } from './room-thread.ts';
import type { MovingRoom, WorkerInit, WorkerRoomConfig } from './worker-protocol.ts';

/** Options of WorkerPool.start. */
export interface WorkerPoolOptions {
  /** How many room workers (≥ 1). */
  count: number;
  config: WorkerRoomConfig;
  /** Modules exporting extra ScenarioDefinitions for the workers (file URLs). */
  scenarioModules?: readonly string[];
  logLevel: string;
  logger: Logger;
  /** CPU ms per tick a worker may fill. Default WORKER_BUDGET_MS_PER_TICK. */
  budgetMsPerTick?: number;
  /** How often the move policy (move-policy.ts) looks at the workers' loads; 0: never (moves only on request). Default 1000. */
  moveCheckEveryMs?: number;
  /** Each worker's young-generation size in MB (Worker resourceLimits.maxYoungGenerationSizeMb). Default: V8's. */
  youngGenerationMb?: number;
}

/** A room that moved stays where it is for this long before the policy may move it again. */
export const MOVE_COOLDOWN_MS = 30_000;

/** What asked for a move: the pool's policy, or a caller (moveRoom). */
export type MoveTrigger = 'policy' | 'request';

/** One worker's load for /metrics, the room list and placement. */
export interface WorkerLoad {
  worker: number;
  rooms: number;
  /** Sum of its rooms' CPU ms per tick (measured, or estimated until measured). */
  loadMs: number;
  headroomMs: number;
  externalBytes: number;
}

/** The pool of room workers. */
export class WorkerPool implements RoomHost {
  readonly budgetMsPerTick: number;
  private readonly opts: WorkerPoolOptions;
  private readonly threads: Array<RoomThread | null>;
  private stopped = false;
  private moving = false;
  /** When each room last moved (performance.now()). */
  private readonly movedAt = new Map<string, number>();
  private moveMetrics: { moves: Counter<'trigger'>; pause: Histogram } | null = null;
  private readonly moveTimer: ReturnType<typeof setInterval> | null = null;

  private constructor(opts: WorkerPoolOptions) {
    this.opts = opts;
    this.budgetMsPerTick = opts.budgetMsPerTick ?? WORKER_BUDGET_MS_PER_TICK;
    this.threads = new Array<RoomThread | null>(opts.count).fill(null);
    const everyMs = opts.moveCheckEveryMs ?? 1000;
    if (everyMs > 0 && opts.count > 1) {
      this.moveTimer = setInterval(() => void this.rebalance(), everyMs);
      this.moveTimer.unref();
    }
  }

  /** Starts `count` workers and waits until every one is ready. */
  static async start(opts: WorkerPoolOptions): Promise<WorkerPool> {
    if (!Number.isInteger(opts.count) || opts.count < 1 || opts.count > 256) throw new Error(`room workers must be a whole number in [1, 256], got ${opts.count}`);
    if (opts.youngGenerationMb !== undefined && !(opts.youngGenerationMb >= 1 && opts.youngGenerationMb <= 1024)) throw new Error(`a room worker's young generation must be 1–1024 MB, got ${opts.youngGenerationMb}`);
    const pool = new WorkerPool(opts);
    const started = await Promise.allSettled(pool.threads.map((_, i) => pool.spawn(i)));
    const failed = started.find((s) => s.status === 'rejected');
    if (failed) {
      await pool.stop();
      throw failed.reason instanceof Error ? failed.reason : new Error(String(failed.reason));
    }
    return pool;
  }

  /** The running workers (a dead one is replaced; its slot is empty until the new one is ready). */
  workers(): RoomThread[] {
    return this.threads.filter((t): t is RoomThread => t !== null && !t.dead);
  }

  /** Every running worker's load. */
  loads(): WorkerLoad[] {
    return this.workers().map((t) => {
      let loadMs = 0;
      for (const room of t.rooms.values()) loadMs += roomTickCpuMs(room);
      return { worker: t.index, rooms: t.rooms.size, loadMs, headroomMs: this.budgetMsPerTick - loadMs, externalBytes: t.externalBytes };
    });
  }

  /** Opens a room on the worker with the most headroom; throws RoomError(ServerFull) when none has enough. */
  async open(spec: RoomSpec): Promise<RemoteRoom> {
    if (this.stopped) throw new RoomError(ErrorCode.Internal, 'the server is shutting down');
    const placed = placeRoom(this.loads(), estimateTickCpuMs(spec.scenario, spec.params), spec.scenario, this.budgetMsPerTick);
    if ('refusal' in placed) throw new RoomError(ErrorCode.ServerFull, placed.refusal);
    const thread = this.threads[placed.worker];
    if (!thread) throw new RoomError(ErrorCode.ServerFull, `room worker ${placed.worker} is restarting; try again shortly`);
    return thread.open(spec);
  }

  /**
   * Moves a room to another worker (`to`, else the one with the most headroom for its cost) without disconnecting its
   * players: the old worker stops it between two ticks and hands over its checkpoint, input buffers, queues and log;
   * the new one goes on from the next tick. On failure the room goes on where it was (or, when that fails too, closes
   * with the reason) and this rejects.
   */
  async moveRoom(roomId: string, opts: { to?: number; reason?: string; trigger?: MoveTrigger } = {}): Promise<RoomMoveSummary> {
    if (this.stopped) throw new RoomError(ErrorCode.Internal, 'the server is shutting down');
    if (this.moving) throw new RoomError(ErrorCode.Internal, 'another room is moving; try again shortly');
    const from = this.workers().find((t) => t.rooms.has(roomId));
    const room = from?.rooms.get(roomId);
    if (!from || !room) throw new RoomError(ErrorCode.RoomNotFound, `room ${roomId} is not open in a room worker`);
    const to = this.target(from, room, opts.to);
    const reason = opts.reason ?? 'requested';
    this.moving = true;
    try {
      // The new worker builds the room's simulation (a fresh Jolt module) while the room still runs where it is.
      await to.prepareRoom(room);
      const started = performance.now();
      room.beginMove();
      let moving: MovingRoom;
      try {
        moving = await from.exportRoom(roomId);
      } catch (error) {
        to.discardPrepared(roomId);
        room.endMove(from, from.index, null);
        throw error;
      }
      const exportedMs = performance.now() - started;
      const routes = from.releaseRoom(room);
      try {
        await to.importRoom(room, routes, moving);
      } catch (error) {
        this.opts.logger.error({ room: roomId, from: from.index, to: to.index, err: error }, 'room could not move; it goes on in its old worker');
        try {
          await from.importRoom(room, routes, moving);
        } catch (again) {
          room.endMove(from, from.index, null);
          room.closedBy(`room error: it could not move to another worker (${again instanceof Error ? again.message : String(again)})`, routes.map(([, r]) => r.sink));
          throw again;
        }
        room.endMove(from, from.index, null);
        throw error;
      }
      const summary: RoomMoveSummary = { from: from.index, to: to.index, tick: moving.carry.tick, pauseMs: performance.now() - started, reason };
      room.endMove(to, to.index, summary);
      this.movedAt.set(roomId, performance.now());
      this.moveMetrics?.moves.inc({ trigger: opts.trigger ?? 'request' });
      this.moveMetrics?.pause.observe(summary.pauseMs / 1000);
      this.opts.logger.info({ room: roomId, ...summary, pauseMs: Math.round(summary.pauseMs * 10) / 10, exportMs: Math.round(exportedMs * 10) / 10, players: moving.members.length, recording: moving.carry.log?.path ?? null }, 'room moved to another worker');
      return summary;
    } finally {
      this.moving = false;
    }
  }

  /** Whether a room is moving now (one at a time). */
  get isMoving(): boolean {
    return this.moving;
  }

  /** Applies the move policy once (the pool does so on its own every moveCheckEveryMs); the move made, or null. */
  async rebalance(): Promise<MovePlan | null> {
    if (this.moving || this.stopped) return null;
    const now = performance.now();
    const skip = new Set<string>();
    for (const [id, at] of this.movedAt) {
      if (now - at < MOVE_COOLDOWN_MS) skip.add(id);
      else this.movedAt.delete(id);
    }
    const plan = planMove(this.policyView(), this.budgetMsPerTick, skip);
    if (!plan) return null;
    try {
      await this.moveRoom(plan.room, { to: plan.to, reason: plan.reason, trigger: 'policy' });
      return plan;
    } catch (error) {
      this.movedAt.set(plan.room, performance.now()); // not again at once
      this.opts.logger.warn({ room: plan.room, from: plan.from, to: plan.to, err: error }, 'the move policy could not move a room');
      return null;
    }
  }

  /** The workers and their rooms as the move policy sees them. */
  policyView(): PolicyWorker[] {
    return this.workers().map((t) => ({
      worker: t.index,
      rooms: [...t.rooms.values()].map((r) => ({ id: r.id, costMs: roomTickCpuMs(r), estimateMs: estimateTickCpuMs(r.scenarioName, r.params), measured: r.status?.tickCpuMs != null, missingBudget: r.status?.slow ?? false })),
    }));
  }

  private target(from: RoomThread, room: RemoteRoom, to: number | undefined): RoomThread {
    if (to !== undefined) {
      const thread = this.threads[to];
      if (!thread || thread.dead) throw new RoomError(ErrorCode.ServerFull, `room worker ${to} is not running`);
      if (thread === from) throw new RoomError(ErrorCode.BadMessage, `room ${room.id} already runs in worker ${to}`);
      return thread;
    }
    const placed = placeRoom(this.loads().filter((l) => l.worker !== from.index), roomTickCpuMs(room), room.scenarioName, this.budgetMsPerTick);
    if ('refusal' in placed) throw new RoomError(ErrorCode.ServerFull, placed.refusal);
    const thread = this.threads[placed.worker];
    if (!thread) throw new RoomError(ErrorCode.ServerFull, `room worker ${placed.worker} is restarting; try again shortly`);
    return thread;
  }

  /**
   * Adds the workers' load to a registry (read at scrape time): taos_room_worker_cpu_ms_per_tick{worker} (its rooms'
   * CPU per tick, measured or estimated), taos_room_worker_headroom_ms{worker} and taos_room_worker_rooms{worker}.
   */
  registerMetrics(registry: Registry, prefix = 'taos_'): void {
    const loads = (): WorkerLoad[] => this.loads();
    const gauge = (name: string, help: string, value: (l: WorkerLoad) => number): void => {
      new Gauge({
        name: `${prefix}${name}`,
        help,
        labelNames: ['worker'],
        registers: [registry],
        collect() {
          this.reset();
          for (const l of loads()) this.set({ worker: String(l.worker) }, value(l));
        },
      });
    };
    gauge('room_worker_cpu_ms_per_tick', "Each room worker's rooms' CPU ms per tick (measured; estimated until a room has ticked)", (l) => l.loadMs);
    gauge('room_worker_headroom_ms', 'CPU ms per tick a room worker has left under its budget (negative: over it, running at the lowest priority)', (l) => l.headroomMs);
    gauge('room_worker_rooms', 'Rooms open in each room worker', (l) => l.rooms);
    this.moveMetrics = {
      moves: new Counter({ name: `${prefix}room_moves_total`, help: 'Rooms moved to another room worker, by what asked (policy: one proved heavier than estimated beside rooms missing their budget)', labelNames: ['trigger'], registers: [registry] }),
      pause: new Histogram({ name: `${prefix}room_move_pause_seconds`, help: "How long a moving room's players saw no tick", buckets: [0.005, 0.01, 0.025, 0.05, 0.1, 0.25, 0.5, 1, 2.5], registers: [registry] }),
    };
  }

  /** Every worker's metrics as prom-client JSON (workers that do not answer in time are left out). */
  async metricsJson(timeoutMs = 1000): Promise<unknown[]> {
    const all = await Promise.all(this.workers().map((t) => t.metricsJson(timeoutMs)));
    return all.filter((m) => m !== null);
  }

  /** Ends every worker (rooms must have been closed first: their recordings end there). */
  async stop(): Promise<void> {
    this.stopped = true;
    if (this.moveTimer) clearInterval(this.moveTimer);
    await Promise.all(this.threads.map((t) => t?.stop()));
  }

  private init(index: number): WorkerInit {
    return { index, count: this.opts.count, scenarioModules: this.opts.scenarioModules ?? [], logLevel: this.opts.logLevel, config: this.opts.config };
  }

  private async spawn(index: number): Promise<void> {
    const thread = await RoomThread.start(this.init(index), this.opts.logger, (dead, why) => this.replace(dead, why), this.opts.youngGenerationMb);
    if (this.stopped) {
      await thread.stop();
      return;
    }
    this.threads[index] = thread;
  }

  // A worker died: its rooms are closed already; a fresh worker takes its place so the server keeps its capacity.
  private replace(dead: RoomThread, why: string): void {
    if (this.stopped || this.threads[dead.index] !== dead) return;
    this.threads[dead.index] = null;
    this.opts.logger.warn({ worker: dead.index, why }, 'starting a new room worker in place of the one that died');
    this.spawn(dead.index).catch((error: unknown) => this.opts.logger.error({ worker: dead.index, err: error }, 'a replacement room worker failed to start'));
  }
}
