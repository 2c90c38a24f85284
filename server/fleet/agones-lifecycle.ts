// The Agones GameServer lifecycle through the official SDK (@google-cloud/agones-sdk, gRPC to the sidecar): Ready once
// listening, Health on a timer, the players counter, rooms list and labels kept current, Allocate when the first
// player joins a single-session server, and Shutdown after a drain when its session is over or the process stops.
// SDK calls never run in the tick and never throw out of a timer: failures are logged once and retried or dropped.
import type { Clock, TimerHandle } from '../../shared/clock.ts';
import type { Logger } from '../logger.ts';
import type { HostedRoom } from '../hosted-room.ts';
import { DEFAULT_ROOM_ID } from '../room-manager.ts';

/** The part of the SDK's AgonesSDK this lifecycle uses (its bundled typings omit `beta`). */
export interface AgonesClient {
  connect(): Promise<void>;
  ready(): Promise<unknown>;
  allocate(): Promise<unknown>;
  shutdown(): Promise<unknown>;
  health(errorCallback?: (error: Error) => void): void;
  setLabel(key: string, value: string): Promise<unknown>;
  getGameServer(): Promise<AgonesGameServer>;
  watchGameServer(callback: (gameServer: AgonesGameServer) => void, errorCallback?: (error: Error) => void): void;
  close(): void;
  beta: {
    setCounterCount(key: string, amount: number): Promise<void>;
    setCounterCapacity(key: string, amount: number): Promise<void>;
    appendListValue(key: string, value: string): Promise<void>;
    deleteListValue(key: string, value: string): Promise<void>;
  };
}

/** What this lifecycle reads of a GameServer (the SDK's toObject() shape). */
export interface AgonesGameServer {
  status?: { state?: string; address?: string; portsList?: Array<{ name?: string; port?: number }> };
}

/**
 * Where players reach a GameServer: its node's address and its first port (Agones maps the container port to it), as
 * an http(s) base URL; null while Agones has not assigned them.
 */
export function gameServerUrl(gs: AgonesGameServer, secure: boolean): string | null {
  const address = gs.status?.address ?? '';
  const port = gs.status?.portsList?.find((p) => typeof p.port === 'number' && p.port > 0)?.port;
  if (address === '' || port === undefined) return null;
  const host = address.includes(':') ? `[${address}]` : address;
  return `${secure ? 'https' : 'http'}://${host}:${port}/`;
}

/** The rooms the lifecycle watches (RoomManager). */
export interface WatchedRooms {
  all(): HostedRoom[];
  clientCount(): number;
  onRoomOpened(fn: (room: HostedRoom) => void): () => void;
}

/** Options of AgonesLifecycle. */
export interface AgonesOptions {
  client: AgonesClient;
  rooms: WatchedRooms;
  clock: Clock;
  logger: Logger;
  /** Allocate when the first player joins, and shut down once the session is over. Default false. */
  singleSession?: boolean;
  /** How long a finished session stays idle before Shutdown (players may reconnect meanwhile). Default 5000 ms. */
  drainMs?: number;
  /** Milliseconds between Health pings. Default 2000. */
  healthIntervalMs?: number;
  /** Capacity of the `players` counter (the server's connection limit). */
  maxPlayers: number;
  /** Closes the server when a single-session server's session is over (it calls shutdown() when done). */
  onSessionOver(reason: string): void;
}

/** Names of what is published on the GameServer. */
export const AgonesKeys = {
  /** Counter and label: players in all rooms. */
  players: 'players',
  /** List: ids of the open rooms; label `rooms`: how many. */
  rooms: 'rooms',
} as const;

/** The environment variables the Agones sidecar sets in a game server's container. */
export const AGONES_ENV = ['AGONES_SDK_GRPC_PORT', 'AGONES_SDK_HTTP_PORT'] as const;

/** Whether the process runs beside an Agones SDK sidecar (its environment is set). */
export function agonesSidecarPresent(env: NodeJS.ProcessEnv = process.env): boolean {
  return AGONES_ENV.some((name) => env[name] !== undefined && env[name] !== '');
}

/** Builds the official SDK client (it reads AGONES_SDK_GRPC_PORT, default 9357, on localhost). */
export async function createAgonesClient(): Promise<AgonesClient> {
  // A CommonJS package: its module.exports (the AgonesSDK class) is the ES default export.
  const mod = (await import('@google-cloud/agones-sdk')) as unknown as { default: new () => unknown };
  return new mod.default() as AgonesClient;
}

const errorText = (error: unknown): string => (error instanceof Error ? error.message : String(error));

/** One game server's life under Agones. */
export class AgonesLifecycle {
  private readonly opts: AgonesOptions;
  private readonly drainMs: number;
  private healthTimer: TimerHandle | null = null;
  private publishTimer: TimerHandle | null = null;
  private drainTimer: TimerHandle | null = null;
  private readonly unsubscribe: Array<() => void> = [];
  private inFlight: Promise<void> | null = null;
  private publishAgain = false;
  private stopping = false;
  private published = { players: -1, rooms: new Set<string>(), roomCount: -1 };
  private countsAndLists = true;
  private readonly warned = new Set<string>();
  private allocated = false;
  private allocating = false;
  private stopped: Promise<void> | null = null;

  constructor(opts: AgonesOptions) {
    this.opts = opts;
    this.drainMs = opts.drainMs ?? 5000;
  }

  /** Whether the GameServer is Allocated (by this server or by an allocation from outside). */
  get isAllocated(): boolean {
    return this.allocated;
  }

  private warnOnce(kind: string, error: unknown): void {
    if (this.warned.has(kind)) return;
    this.warned.add(kind);
    this.opts.logger.warn({ err: errorText(error) }, `agones: ${kind} failed`);
  }

  private sidecarError(error: unknown): Error {
    return new Error(`cannot reach the Agones SDK sidecar on localhost:${process.env.AGONES_SDK_GRPC_PORT ?? 9357}: ${errorText(error)}`, { cause: error });
  }

  /** Connects to the sidecar (the SDK waits up to 30 s); throws a clear Error when it does not answer. */
  async connect(): Promise<void> {
    try {
      await this.opts.client.connect();
    } catch (error) {
      throw this.sidecarError(error);
    }
  }

  /** Where Agones says players reach this GameServer (see gameServerUrl), or null. */
  async publicUrl(secure: boolean): Promise<string | null> {
    try {
      return gameServerUrl(await this.opts.client.getGameServer(), secure);
    } catch (error) {
      this.warnOnce('GetGameServer', error);
      return null;
    }
  }

  /** Marks the server Ready (after connect) and starts Health, the watch and publishing. */
  async start(): Promise<void> {
    const { client } = this.opts;
    try {
      await client.ready();
    } catch (error) {
      throw this.sidecarError(error);
    }
    this.opts.logger.info({ singleSession: this.opts.singleSession ?? false }, 'agones: Ready');
    const beat = (): void => {
      client.health((error) => this.warnOnce('Health', error));
      this.healthTimer = this.opts.clock.setTimer(this.opts.healthIntervalMs ?? 2000, beat);
    };
    beat();
    client.watchGameServer(
      (gs) => {
        if (gs.status?.state === 'Allocated' && !this.allocated) {
          this.allocated = true;
          this.opts.logger.info('agones: Allocated');
          this.changed();
        }
      },
      (error) => this.warnOnce('WatchGameServer', error),
    );
    client.beta.setCounterCapacity(AgonesKeys.players, this.opts.maxPlayers).catch((error: unknown) => this.countsOff(error));
    const watch = (room: HostedRoom): void => {
      this.unsubscribe.push(room.onEmptyChange(() => this.changed()));
      this.unsubscribe.push(room.onClose(() => this.opts.clock.setTimer(0, () => this.changed())));
      this.changed();
    };
    for (const room of this.opts.rooms.all()) watch(room);
    this.unsubscribe.push(this.opts.rooms.onRoomOpened(watch));
    this.changed();
  }

  /** Counters and lists must be declared in the GameServer spec; without them only labels are published. */
  private countsOff(error: unknown): void {
    if (!this.countsAndLists) return;
    this.countsAndLists = false;
    this.opts.logger.warn({ err: errorText(error) }, `agones: the "${AgonesKeys.players}" counter or "${AgonesKeys.rooms}" list is not declared on this GameServer; publishing labels only`);
  }

  /** Players or rooms changed: allocate, drain or publish as the new state asks. */
  private changed(): void {
    if (this.stopped) return;
    const players = this.opts.rooms.clientCount();
    if (this.opts.singleSession && players > 0 && !this.allocated && !this.allocating) {
      this.allocating = true;
      this.opts.client.allocate().then(
        () => {
          this.allocated = true;
          this.allocating = false;
          this.opts.logger.info({ players }, 'agones: Allocated (first player joined)');
          this.changed();
        },
        (error: unknown) => {
          this.allocating = false;
          this.warnOnce('Allocate', error);
        },
      );
    }
    const sessionRooms = this.opts.rooms.all().filter((r) => r.id !== DEFAULT_ROOM_ID).length;
    const idle = this.opts.singleSession === true && this.allocated && players === 0 && sessionRooms === 0;
    if (idle && this.drainTimer === null) {
      this.drainTimer = this.opts.clock.setTimer(this.drainMs, () => {
        this.drainTimer = null;
        if (this.opts.rooms.clientCount() === 0) this.opts.onSessionOver('the session is over (no players, no rooms)');
      });
    } else if (!idle && this.drainTimer !== null) {
      this.opts.clock.clearTimer(this.drainTimer);
      this.drainTimer = null;
    }
    if (this.publishTimer === null) {
      this.publishTimer = this.opts.clock.setTimer(50, () => {
        this.publishTimer = null;
        this.publish();
      });
    }
  }

  /** Brings labels, the players counter and the rooms list up to date (one update in flight at a time). */
  private publish(): void {
    if (this.inFlight) {
      this.publishAgain = true;
      return;
    }
    this.inFlight = this.publishOnce().finally(() => {
      this.inFlight = null;
      if (this.publishAgain && !this.stopping) {
        this.publishAgain = false;
        this.publish();
      }
    });
  }

  private async publishOnce(): Promise<void> {
    const { client } = this.opts;
    // Each step checks `stopping`: nothing is published after Shutdown.
    const players = this.opts.rooms.clientCount();
    const rooms = new Set(this.opts.rooms.all().map((r) => r.id));
    if (players !== this.published.players && !this.stopping) {
      await client.setLabel(AgonesKeys.players, String(players)).catch((error: unknown) => this.warnOnce('SetLabel', error));
      if (this.countsAndLists && !this.stopping) await client.beta.setCounterCount(AgonesKeys.players, players).catch((error: unknown) => this.countsOff(error));
      this.published.players = players;
    }
    if (rooms.size !== this.published.roomCount && !this.stopping) {
      await client.setLabel(AgonesKeys.rooms, String(rooms.size)).catch((error: unknown) => this.warnOnce('SetLabel', error));
      this.published.roomCount = rooms.size;
    }
    for (const id of [...rooms].sort()) {
      if (this.published.rooms.has(id) || !this.countsAndLists || this.stopping) continue;
      await client.beta.appendListValue(AgonesKeys.rooms, id).catch((error: unknown) => this.countsOff(error));
      this.published.rooms.add(id);
    }
    for (const id of [...this.published.rooms].sort()) {
      if (rooms.has(id) || !this.countsAndLists || this.stopping) continue;
      await client.beta.deleteListValue(AgonesKeys.rooms, id).catch((error: unknown) => this.countsOff(error));
      this.published.rooms.delete(id);
    }
  }

  /** Tells Agones the server is done (Shutdown) and closes the SDK link; idempotent. Never throws. */
  shutdown(reason: string): Promise<void> {
    this.stopped ??= (async () => {
      this.stopping = true;
      for (const timer of [this.healthTimer, this.publishTimer, this.drainTimer]) if (timer) this.opts.clock.clearTimer(timer);
      for (const off of this.unsubscribe.splice(0)) off();
      await this.inFlight;
      try {
        await this.opts.client.shutdown();
        this.opts.logger.info({ reason }, 'agones: Shutdown');
      } catch (error) {
        this.opts.logger.warn({ err: errorText(error), reason }, 'agones: Shutdown failed');
      }
      this.opts.client.close();
    })();
    return this.stopped;
  }
}
