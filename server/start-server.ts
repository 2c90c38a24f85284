// Starts the networked server on one port: HTTP routes + static client + WebSocket gateway around a GameServer whose
// rooms run the registered scenarios; close(reason) shuts it all down in order (byes, rooms, recordings, sockets, logs).
import './physics-node.ts';
import type { AddressInfo } from 'node:net';
import { dirname, join, resolve } from 'node:path';
import { fileURLToPath } from 'node:url';
import { DEFAULT_SCENARIO, listScenarios } from '../scenarios/index.ts';
import { MAX_CLIENT_MESSAGE_BYTES } from '../shared/protocol/index.ts';
import { resolveParams } from '../shared/sim/scenario.ts';
import { SystemClock, type Clock } from './clock.ts';
import type { SessionLimits } from './client-session.ts';
import { GameServer } from './game-server.ts';
import { createHttpApi } from './http-api.ts';
import { createHttpServer } from './http-server.ts';
import { createLogger, flushLogger, type Logger } from './logger.ts';
import { createMetrics, type ServerMetrics } from './metrics.ts';
import { createRoomFactory, type ScenarioSource } from './room-factory.ts';
import { createStaticHandler } from './static-files.ts';
import { attachWsGateway } from './ws-gateway.ts';

const REPO_ROOT = resolve(dirname(fileURLToPath(import.meta.url)), '..');
/** Where the built browser client is served from by default. */
export const DEFAULT_CLIENT_DIR = join(REPO_ROOT, 'dist', 'client');

/** Options of startServer (the serve command's flags plus test hooks). */
export interface StartServerOptions {
  /** Port to listen on; 0 picks a free one. Default 8080. */
  port?: number;
  /** Interface to bind. Default 127.0.0.1. */
  host?: string;
  /** Default room's scenario. Default character-course. */
  scenario?: string;
  params?: Readonly<Record<string, number>>;
  seed?: number | string;
  /** Snapshots per second per client (1–60). Default 30. */
  snapshotRateHz?: number;
  /** Record every room's input log here. */
  recordDir?: string | null;
  /** Most clients per room. Default 32. */
  maxClients?: number;
  maxConnections?: number;
  maxRooms?: number;
  emptyRoomGraceMs?: number;
  /** Directory of the built client. Default dist/client. */
  clientDir?: string;
  clock?: Clock;
  logger?: Logger;
  metrics?: ServerMetrics;
  limits?: Partial<SessionLimits>;
  /** Scenarios to offer; default the built-in registry. */
  scenarios?: ScenarioSource;
  /** Milliseconds between WebSocket keep-alive pings. Default 15000. */
  heartbeatMs?: number;
}

/** A listening server. */
export interface RunningServer {
  /** http://host:port/ */
  readonly url: string;
  /** ws://host:port/ */
  readonly wsUrl: string;
  readonly port: number;
  readonly host: string;
  readonly game: GameServer;
  readonly logger: Logger;
  /** Shuts down: clients get a bye with `reason`, rooms stop, recordings end, sockets close, logs flush. Idempotent. */
  close(reason?: string): Promise<void>;
}

/** The built-in scenario registry as a ScenarioSource. */
export function registryScenarios(): ScenarioSource {
  return {
    get: (name) => listScenarios().find((s) => s.name === name),
    names: () => listScenarios().map((s) => s.name),
  };
}

/** Starts listening; throws a clear Error for a bad scenario/parameter or a port that cannot be bound. */
export async function startServer(opts: StartServerOptions = {}): Promise<RunningServer> {
  const logger = opts.logger ?? createLogger();
  const metrics = opts.metrics ?? createMetrics();
  const clock = opts.clock ?? new SystemClock();
  const scenarios = opts.scenarios ?? registryScenarios();
  const scenarioName = opts.scenario ?? DEFAULT_SCENARIO;
  const def = scenarios.get(scenarioName);
  if (!def) throw new Error(`unknown scenario "${scenarioName}" (known: ${scenarios.names().join(', ')})`);
  resolveParams(def, opts.params ?? {}); // a clear Error before anything is started
  const port = opts.port ?? 8080;
  const host = opts.host ?? '127.0.0.1';
  if (!Number.isInteger(port) || port < 0 || port > 65535) throw new Error(`port must be an integer in [0, 65535], got ${port}`);

  const game = await GameServer.create({
    factory: createRoomFactory({ scenarios, logger, recordDir: opts.recordDir ?? null }),
    defaultScenario: scenarioName,
    defaultParams: opts.params,
    seed: opts.seed,
    clock,
    metrics,
    logger,
    snapshotRateHz: opts.snapshotRateHz,
    maxClientsPerRoom: opts.maxClients,
    maxConnections: opts.maxConnections,
    maxRooms: opts.maxRooms,
    emptyRoomGraceMs: opts.emptyRoomGraceMs,
    limits: opts.limits,
  });

  const staticFiles = createStaticHandler(opts.clientDir ?? DEFAULT_CLIENT_DIR);
  const http = createHttpServer(
    createHttpApi({ game, scenarios, metrics, logger, staticFiles }),
    (error) => logger.error({ err: error }, 'HTTP request failed'),
  );
  const gateway = attachWsGateway(http, {
    clock,
    maxPayloadBytes: opts.limits?.maxMessageBytes ?? MAX_CLIENT_MESSAGE_BYTES,
    heartbeatMs: opts.heartbeatMs,
    refuse: () => game.refusal(),
    onConnection: (conn) => {
      game.accept(conn);
    },
  });

  try {
    await new Promise<void>((resolveListen, rejectListen) => {
      http.once('error', rejectListen);
      http.listen(port, host, () => {
        http.off('error', rejectListen);
        resolveListen();
      });
    });
  } catch (error) {
    await game.close('failed to start');
    await gateway.close(0);
    const e = error as NodeJS.ErrnoException;
    throw new Error(e.code === 'EADDRINUSE' ? `port ${port} on ${host} is already in use (pick another with --port)` : `cannot listen on ${host}:${port}: ${e.message}`, { cause: error });
  }
  const address = http.address() as AddressInfo;
  // Bound to every interface: show the loopback address, which a browser on this machine can open.
  const reachable = host === '0.0.0.0' ? '127.0.0.1' : host === '::' ? '::1' : host;
  const shownHost = reachable.includes(':') ? `[${reachable}]` : reachable;
  const url = `http://${shownHost}:${address.port}/`;
  const wsUrl = `ws://${shownHost}:${address.port}/`;
  logger.info({ url, scenario: scenarioName, snapshotRateHz: game.snapshotRateHz, recordDir: opts.recordDir ?? null }, 'server listening');

  let closing: Promise<void> | null = null;
  return {
    url,
    wsUrl,
    port: address.port,
    host,
    game,
    logger,
    close(reason = 'server shutting down') {
      closing ??= (async () => {
        await game.close(reason);
        await gateway.close(1000);
        http.closeAllConnections();
        await new Promise<void>((done) => http.close(() => done()));
        logger.info({ reason }, 'server stopped');
        await flushLogger(logger);
      })();
      return closing;
    },
  };
}
