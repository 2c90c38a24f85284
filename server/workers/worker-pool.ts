// The room workers of a server (serve --room-workers N): starts them, places each new room on the worker with the most
// headroom by measured (or estimated) CPU per tick, refuses a room no worker has room for (503 with the reason), and
// replaces a worker that died. The RoomManager opens rooms through it instead of on the main thread.
import { Gauge, type Registry } from 'prom-client';
import { ErrorCode } from '../../shared/protocol/opcodes.ts';
import type { Logger } from '../logger.ts';
import { RoomError } from '../room.ts';
import type { RoomHost, RoomSpec } from '../room-manager.ts';
import type { RemoteRoom } from './remote-room.ts';
import { estimateTickCpuMs, placeRoom, roomTickCpuMs, WORKER_BUDGET_MS_PER_TICK } from './room-cost.ts';
import { RoomThread } from './room-thread.ts';
import type { WorkerInit, WorkerRoomConfig } from './worker-protocol.ts';

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
  /** Each worker's young-generation size in MB (Worker resourceLimits.maxYoungGenerationSizeMb). Default: V8's. */
  youngGenerationMb?: number;
}

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

  private constructor(opts: WorkerPoolOptions) {
    this.opts = opts;
    this.budgetMsPerTick = opts.budgetMsPerTick ?? WORKER_BUDGET_MS_PER_TICK;
    this.threads = new Array<RoomThread | null>(opts.count).fill(null);
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
  }

  /** Every worker's metrics as prom-client JSON (workers that do not answer in time are left out). */
  async metricsJson(timeoutMs = 1000): Promise<unknown[]> {
    const all = await Promise.all(this.workers().map((t) => t.metricsJson(timeoutMs)));
    return all.filter((m) => m !== null);
  }

  /** Ends every worker (rooms must have been closed first: their recordings end there). */
  async stop(): Promise<void> {
    this.stopped = true;
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
