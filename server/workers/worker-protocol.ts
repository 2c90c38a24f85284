// The contract between the main thread (HTTP, sockets, sessions) and a room worker (simulations, snapshot encoding,
// input logs): every message both ways, and the per-flush byte batch a worker hands back as one transferable buffer.
// Plain data only (structured clone); nothing here may hold a function, a socket or a Jolt object.
import type { InputCommand } from '../../shared/sim/input.ts';
import type { WelcomeMessage } from '../../shared/protocol/index.ts';
import type { ErrorCode } from '../../shared/protocol/opcodes.ts';
import type { DeliveryKind, RoomEntry } from '../hosted-room.ts';
import type { RoomInfo } from '../room.ts';
import type { DurabilityOptions } from '../recorder.ts';
import type { NetModeRequest } from '../net-mode-policy.ts';
import type { PredictState } from '../member-delivery.ts';
import type { RoomCarry } from '../room-carry.ts';

/** Room settings every room of a worker shares (the serve flags). */
export interface WorkerRoomConfig {
  snapshotRateHz: number;
  maxClientsPerRoom: number;
  maxCatchUpTicks?: number;
  maxInputLeadTicks?: number;
  pauseWhenEmpty?: boolean;
  /** Record every room's input log into this directory (null: no recording). */
  recordDir: string | null;
  recordHashEveryTicks?: number;
  /** CPU ms per tick the worker's rooms may use before it lowers its own OS priority. */
  budgetMsPerTick: number;
  durability?: DurabilityOptions;
  checkpointEverySeconds?: number;
}

/** What a worker starts with (workerData). */
export interface WorkerInit {
  /** Which worker of the pool this is (logs, tick phase offset). */
  index: number;
  /** How many workers the pool has. */
  count: number;
  /** Modules whose exported ScenarioDefinitions the worker offers besides the built-in registry (file URLs). */
  scenarioModules: readonly string[];
  logLevel: string;
  config: WorkerRoomConfig;
}

/** A room's figures as the worker measured them, pushed every STATUS_INTERVAL_MS. */
export interface RoomStatus {
  id: string;
  tick: number;
  clients: number;
  bodies: number;
  heap: { usedBytes: number; freeBytes: number } | null;
  /** Ticks run per second over the last window (60 when keeping up, 0 when paused). */
  ticksPerSecond: number;
  /** Mean CPU ms of its thread per tick over the last window (null before the room has ticked). */
  tickCpuMs: number | null;
  /** True while the room cannot keep 60 Hz (it gave up ticks within the last 2 s). */
  slow: boolean;
  /** 99th percentile of its last 600 tick times (ms). */
  tickMsP99: number | null;
  /** 99th percentile of the CPU time of its last 600 ticks (ms). */
  tickCpuMsP99: number | null;
  /** Longest time between two tick starts among its last 600 ticks (ms). */
  tickGapMsMax: number | null;
  /** Ticks given up since the room opened. */
  skippedTicks: number;
  /** [playerId, missed input ticks] pairs, flat. */
  missedInputTicks: number[];
}

/** Numbers per GC pause in a status: start (ms since the Unix epoch), duration (ms), kind (perf_hooks' gc kind). */
export const GC_PAUSE_FIELDS = 3;

/** How often a worker pushes its rooms' status. */
export const STATUS_INTERVAL_MS = 250;

/** Main → worker. `req` numbers a request whose answer is a `reply` with the same number. */
export type ToWorker =
  | { t: 'open'; req: number; id: string; scenario: string; params: Readonly<Record<string, number>>; seed: number | string; netMode?: NetModeRequest }
  | { t: 'enter'; req: number; room: string; member: number; entry: RoomEntry }
  | { t: 'leave'; room: string; player: number }
  | { t: 'detach'; room: string; player: number }
  | { t: 'close'; req: number; room: string; reason: string }
  | { t: 'traffic'; traffic: MemberTraffic }
  | { t: 'metrics'; req: number }
  /** Build a fresh simulation for a room about to move in (the slow part of a move, done before the room stops). */
  | { t: 'prepare'; req: number; room: string; scenario: string; params: Readonly<Record<string, number>>; seed: number | string }
  /** Drop a prepared simulation (the move did not happen). */
  | { t: 'discard'; room: string }
  /** Stop a room between two ticks and hand it back (answers a MovingRoom; the room is gone from the worker). */
  | { t: 'export'; req: number; room: string }
  /** Go on with a room another worker exported (answers an OpenedRoom). */
  | { t: 'import'; req: number; moving: MovingRoom };

/** A member of a moving room: the same member id on the main thread, and where its predict stream stands. */
export interface CarriedMember {
  member: number;
  playerId: number;
  predict: PredictState;
}

/** A room between two workers: its state and its connected members. */
export interface MovingRoom {
  carry: RoomCarry;
  members: CarriedMember[];
}

/** What members sent since the last flush, and whose sockets changed backed-up state (flat tuples). */
export interface MemberTraffic {
  /** Each input message of a member: the first tick it stamps and its commands. */
  inputs: Array<{ member: number; firstTick: number; commands: InputCommand[] }>;
  /** Each game message of a member, in arrival order. */
  messages: Array<{ member: number; name: string; payload: number[]; tick?: number }>;
  /** [member, tick] pairs, flat. */
  acks: number[];
  /** [member, 1 | 0] pairs, flat: the member's socket is (no longer) backed up. */
  pressure: number[];
  /** [member, 1 | 0] pairs, flat: serve the member in predict mode (again: a resync) or on snapshots. */
  netModes: number[];
}

/** What an `open` answers. */
export interface OpenedRoom {
  info: RoomInfo;
  /** The room's input log (null: not recording), so the main thread can keep resume keys beside it. */
  recordingPath: string | null;
}

/** What an `enter` answers. */
export interface EnteredRoom {
  playerId: number;
  welcome: WelcomeMessage;
}

/** Worker → main. */
export type FromWorker =
  | { t: 'ready' }
  | { t: 'reply'; req: number; ok: true; value: unknown }
  | { t: 'reply'; req: number; ok: false; code: ErrorCode | null; message: string }
  | { t: 'out'; batch: ByteBatch; ticks: Array<[room: string, tick: number]> }
  | { t: 'gone'; member: number; closed: boolean; reason: string }
  | { t: 'closed'; room: string; reason: string }
  | { t: 'status'; rooms: RoomStatus[]; externalBytes: number; gcPauses: number[] }
  /** One JSON log line of the worker's logger; the main thread's logger writes it. */
  | { t: 'log'; line: string };

/** One flush of member bytes: the distinct messages packed into `buffer`, and [member, offset, length, kind] quads. */
export interface ByteBatch {
  buffer: ArrayBuffer;
  sends: Int32Array;
}

/** Collects deliveries until flushed; a message shared by many members is packed once. */
export class ByteBatcher {
  private readonly order: Uint8Array[] = [];
  private readonly sends: number[] = [];
  private readonly seen = new Map<Uint8Array, number>();
  private bytes = 0;

  /** Whether nothing is waiting. */
  get empty(): boolean {
    return this.sends.length === 0;
  }

  add(member: number, message: Uint8Array, kind: DeliveryKind): void {
    let index = this.seen.get(message);
    if (index === undefined) {
      index = this.order.length;
      this.seen.set(message, index);
      this.order.push(message);
      this.bytes += message.length;
    }
    this.sends.push(member, index, message.length, kind);
  }

  /** Packs everything into one buffer (to transfer) and starts over. */
  take(): ByteBatch {
    const buffer = new ArrayBuffer(this.bytes);
    const view = new Uint8Array(buffer);
    const offsets: number[] = [];
    let at = 0;
    for (const m of this.order) {
      offsets.push(at);
      view.set(m, at);
      at += m.length;
    }
    const sends = new Int32Array(this.sends.length);
    for (let i = 0; i < this.sends.length; i += 4) {
      sends[i] = this.sends[i];
      sends[i + 1] = offsets[this.sends[i + 1]];
      sends[i + 2] = this.sends[i + 2];
      sends[i + 3] = this.sends[i + 3];
    }
    this.order.length = 0;
    this.sends.length = 0;
    this.seen.clear();
    this.bytes = 0;
    return { buffer, sends };
  }
}

/** Calls `fn(member, bytes, kind)` for each send of a batch; `bytes` are views into the batch's buffer. */
export function forEachSend(batch: ByteBatch, fn: (member: number, bytes: Uint8Array, kind: DeliveryKind) => void): void {
  const { sends } = batch;
  for (let i = 0; i < sends.length; i += 4) fn(sends[i], new Uint8Array(batch.buffer, sends[i + 1], sends[i + 2]), sends[i + 3] as DeliveryKind);
}
