// How a started server joins what runs it at scale: the Redis fleet directory (`--redis`) and the Agones lifecycle
// (`--agones`), in the order they need: the sidecar first (it may say where players reach this GameServer), then the
// directory under that public URL, then Ready. Without either option nothing here runs.
import type { Clock } from '../../shared/clock.ts';
import type { GameServer } from '../game-server.ts';
import type { Logger } from '../logger.ts';
import { AgonesLifecycle, createAgonesClient, type AgonesClient } from './agones-lifecycle.ts';
import { FLEET_DEFAULTS, FleetDirectory } from './fleet-directory.ts';

/** Options of a fleet member. */
export interface FleetOptions {
  /** redis:// or rediss:// URL of the directory. */
  redisUrl: string;
  /** Where players reach this process (http:// or https://). Default: Agones's address and port, else the listening address. */
  publicUrl?: string;
  /** Seconds after which a silent member and its rooms leave the directory. Default 10. */
  ttlSeconds?: number;
  /** Key prefix (several fleets may share one Redis). Default `taos:`. */
  prefix?: string;
}

/** Options of the Agones lifecycle. */
export interface AgonesServerOptions {
  /** Allocate when the first player joins; Shutdown once the session is over. Default false. */
  singleSession?: boolean;
  /** Seconds a finished session stays idle before Shutdown. Default 5. */
  drainSeconds?: number;
  /** Milliseconds between Health pings. Default 2000. */
  healthIntervalMs?: number;
  /** The SDK client (tests); default the official SDK on localhost:AGONES_SDK_GRPC_PORT. */
  client?: AgonesClient;
}

/**
 * The directory for `--redis` (not connected yet: rooms need it before the server listens), or null. The Redis client
 * library is loaded here, so a server outside a fleet never loads it.
 */
export async function createFleetDirectory(opts: FleetOptions | undefined, clock: Clock, logger: Logger): Promise<FleetDirectory | null> {
  if (!opts) return null;
  const { Redis } = await import('ioredis');
  return new FleetDirectory({ redisUrl: opts.redisUrl, ttlMs: (opts.ttlSeconds ?? FLEET_DEFAULTS.ttlSeconds) * 1000, prefix: opts.prefix ?? FLEET_DEFAULTS.prefix, clock, logger, redisClass: Redis });
}

/** What joinFleet needs from the listening server. */
export interface JoinContext {
  game: GameServer;
  clock: Clock;
  logger: Logger;
  /** The address the server listens on (http(s)://host:port/). */
  listenUrl: string;
  host: string;
  secure: boolean;
  maxRooms: number;
  /** Closes the server (a single-session server's session is over). */
  closeServer(reason: string): void;
}

/**
 * Connects to the Agones sidecar, starts the fleet directory under the public URL and marks the GameServer Ready.
 * Resolves with the lifecycle (null without Agones); throws a clear Error when the sidecar does not answer.
 */
export async function joinFleet(ctx: JoinContext, directory: FleetDirectory | null, fleet: FleetOptions | undefined, agones: AgonesServerOptions | undefined): Promise<AgonesLifecycle | null> {
  const { game, logger } = ctx;
  let lifecycle: AgonesLifecycle | null = null;
  if (agones) {
    lifecycle = new AgonesLifecycle({
      client: agones.client ?? (await createAgonesClient()),
      rooms: game.rooms,
      clock: ctx.clock,
      logger,
      singleSession: agones.singleSession,
      drainMs: (agones.drainSeconds ?? 5) * 1000,
      healthIntervalMs: agones.healthIntervalMs,
      maxPlayers: game.maxConnections,
      onSessionOver: ctx.closeServer,
    });
    await lifecycle.connect();
  }
  if (directory) {
    const publicUrl = fleet?.publicUrl ?? (await lifecycle?.publicUrl(ctx.secure)) ?? ctx.listenUrl;
    if (publicUrl === ctx.listenUrl && (ctx.host === '0.0.0.0' || ctx.host === '::')) logger.warn({ publicUrl }, 'no --public-url: other servers of the fleet send players to this loopback address');
    await directory.start(publicUrl, () => ({ capacity: { rooms: ctx.maxRooms, connections: game.maxConnections }, players: game.sessionCount(), rooms: game.listRooms() }));
    logger.info({ member: directory.id, publicUrl: directory.url, ttlSeconds: (fleet?.ttlSeconds ?? FLEET_DEFAULTS.ttlSeconds) }, 'joined the fleet');
  }
  await lifecycle?.start();
  return lifecycle;
}
