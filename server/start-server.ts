// Starts the networked server on one port: HTTP routes + static client + WebSocket gateway around a GameServer whose
// rooms run the registered scenarios; close(reason) shuts it all down in order (byes, rooms, recordings, sockets, logs).
import './physics-node.ts';
import type { IncomingMessage, ServerResponse } from 'node:http';
import type { AddressInfo } from 'node:net';
import { DEFAULT_HEAP_GROWING_PERCENT, setHeapGrowingPercent } from './heap-growth.ts';
import type { NetModeRequest } from './net-mode-policy.ts';
import { createSecureContext } from 'node:tls';
import { join } from 'node:path';
import { DEFAULT_SCENARIO, listScenarios } from '../scenarios/index.ts';
import type { Clock } from '../shared/clock.ts';
import { MAX_CLIENT_MESSAGE_BYTES } from '../shared/protocol/index.ts';
import { resolveParams } from '../shared/sim/scenario.ts';
import { createServerAccess, logAccess, type AccessOptions } from './access/access-setup.ts';
import { SystemClock } from './clock.ts';
import type { SessionLimits } from './session-context.ts';
import { GameServer } from './game-server.ts';
import type { AgonesLifecycle } from './fleet/agones-lifecycle.ts';
import type { FleetDirectory } from './fleet/fleet-directory.ts';
import { createFleetDirectory, joinFleet, type AgonesServerOptions, type FleetOptions } from './fleet/fleet-setup.ts';
import { createHttpApi } from './http-api.ts';
import { createHttpServer } from './http-server.ts';
import { ConnectionPolicy, type ConnectionPolicyOptions } from './connection-policy.ts';
import { createTcpGate, Tarpit, type TarpitOptions } from './tcp-gate.ts';
import { createLogger, flushLogger, type Logger } from './logger.ts';
import { createMetrics, type ServerMetrics } from './metrics.ts';
import { PACKAGE_ROOT } from './package-root.ts';
import { createRoomFactory, type ScenarioSource } from './room-factory.ts';
import type { DurabilityOptions } from './recorder.ts';
import { rememberResumeKey, reopenRooms, scanForResume, type ResumeScan } from './resume-rooms.ts';
import { checkReplayLog, withReplayLog } from './replay-log.ts';
import { createStaticHandler } from './static-files.ts';
import { attachWsGateway } from './ws-gateway.ts';
import { WORKER_BUDGET_MS_PER_TICK } from './workers/room-cost.ts';
import { createMonitorRoutes } from './monitor/monitor-routes.ts';
import { ServerMonitor } from './monitor/server-monitor.ts';
import { WorkerPool } from './workers/worker-pool.ts';

/** Where the built browser client is served from by default. */
export const DEFAULT_CLIENT_DIR = join(PACKAGE_ROOT, 'dist', 'client');

/** Options of startServer (the serve command's flags plus test hooks). */
export interface StartServerOptions extends AccessOptions {
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
  /** Net mode of rooms not asked for one ('auto': predict where the cost estimate allows). Default 'auto'. */
  netMode?: NetModeRequest;
  /** Input delay (ticks) predict rooms announce in the welcome (serve --input-delay-ticks). Default 0. */
  inputDelayTicks?: number;
  /** Record every room's input log here. */
  recordDir?: string | null;
  /** A state hash record in recordings every N ticks (default 60; 1 checks every tick on replay). */
  recordHashEveryTicks?: number;
  /** When recorded records reach the disk (--durability). Default tick. */
  durability?: DurabilityOptions;
  /** A checkpoint in recordings every N seconds of play (0: none). Default 10. */
  checkpointEverySeconds?: number;
  /** Reopen the rooms of every interrupted recording in this directory before anything else (serve --resume). */
  resumeDir?: string | null;
  /** Most clients per room. Default 32. */
  maxClients?: number;
  maxConnections?: number;
  maxRooms?: number;
  emptyRoomGraceMs?: number;
  /** Directory of the built client. Default dist/client. */
  clientDir?: string;
  /** An input log the replay viewer (/replay) opens: served at /replay.taoslog. */
  replayFile?: string;
  /** A game's own page folder, served before the built client (its index.html replaces the stock page; the stock
   *  files, /kit.js among them, stay reachable where the folder has no file of that name). */
  pageDir?: string;
  clock?: Clock;
  logger?: Logger;
  metrics?: ServerMetrics;
  limits?: Partial<SessionLimits>;
  /** Scenarios to offer; default the built-in registry. */
  scenarios?: ScenarioSource;
  /** Milliseconds between WebSocket keep-alive pings. Default 15000. */
  heartbeatMs?: number;
  /** How long a player whose link dropped is held for a reconnect (ms). Default 30 000; 0: off. */
  resumeGraceMs?: number;
  /** Per-address connection limits and back-off (defaults: DEFAULT_CONNECTION_POLICY; maxSockets: maxConnections). */
  connectionPolicy?: Partial<ConnectionPolicyOptions>;
  /** How long a socket the server closed may take to finish the close handshake before it is cut. Default 1000 ms. */
  closeGraceMs?: number;
  /** Take the client's address and scheme from X-Forwarded-For/-Proto (only behind a reverse proxy). Default false. */
  trustProxy?: boolean;
  /** How refused connections of one address are held before their answer (see server/tcp-gate.ts). */
  tarpit?: TarpitOptions;
  /** Serve HTTPS and WSS with this certificate chain and private key (PEM). Default: plain HTTP and WS. */
  tls?: { cert: string | Buffer; key: string | Buffer };
  /** Room worker threads to run the rooms in (0: every room on the main thread, as before). Default 0. */
  roomWorkers?: number;
  /** How often the room workers' move policy looks at their loads (ms; 0: rooms move only on request). Default 1000. */
  roomMoveCheckEveryMs?: number;
  /** Modules exporting ScenarioDefinitions the room workers offer beside the registry (file URLs; tests' own scenes). */
  workerScenarioModules?: readonly string[];
  /** Each room worker's young-generation size in MB (fewer, longer scavenges when larger). Default: V8's. */
  roomWorkerYoungGenerationMb?: number;
  /**
   * Old-generation headroom after a full GC, in percent of what it left alive, for the whole process (server/heap-growth.ts;
   * 0: V8's own rule). Default 100: young-generation fills stay scavenges instead of becoming full collections.
   */
  heapGrowingPercent?: number;
  /** Join a fleet of servers through a Redis directory (docs/deploy.md). Default: a single process. */
  fleet?: FleetOptions;
  /** Run as an Agones GameServer through the SDK sidecar (docs/deploy.md). Default: not. */
  agones?: AgonesServerOptions;
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
  /** Who may open a WebSocket (per-address counts, back-off). */
  readonly policy: ConnectionPolicy;
  /** What --resume found: rooms reopened, logs refused (null without --resume). */
  readonly resumed: ResumeScan | null;
  /** This process's membership of the fleet, when started with one. */
  readonly fleet: FleetDirectory | null;
  /** The Agones lifecycle, when run under Agones. */
  readonly agones: AgonesLifecycle | null;
  /** Resolves once the server has closed (by close(), or by itself when a single-session server's session is over). */
  whenClosed(): Promise<void>;
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

/** Throws a clear Error unless `tls` is a PEM certificate chain with its matching private key. */
function checkTls(tls: { cert: string | Buffer; key: string | Buffer }): void {
  try {
    createSecureContext({ cert: tls.cert, key: tls.key });
  } catch (error) {
    throw new Error(`cannot use the TLS certificate and key: ${error instanceof Error ? error.message : String(error)} (both must be PEM; the key must belong to the certificate)`, { cause: error });
  }
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
  if (opts.replayFile) await checkReplayLog(opts.replayFile);
  const access = createServerAccess(opts, metrics, logger);
  if (opts.tls) checkTls(opts.tls);
  const policy = new ConnectionPolicy(clock, { maxSockets: opts.maxConnections ?? 256, ...opts.connectionPolicy });
  const tarpit = new Tarpit(clock, opts.tarpit);
  const fleet = await createFleetDirectory(opts.fleet, clock, logger);

  setHeapGrowingPercent(opts.heapGrowingPercent ?? DEFAULT_HEAP_GROWING_PERCENT);
  const roomWorkers = opts.roomWorkers ?? 0;
  if (!Number.isInteger(roomWorkers) || roomWorkers < 0) throw new Error(`room workers must be a whole number ≥ 0, got ${roomWorkers}`);
  const workers =
    roomWorkers === 0
      ? null
      : await WorkerPool.start({
          count: roomWorkers,
          config: {
            snapshotRateHz: opts.snapshotRateHz ?? 30,
            maxClientsPerRoom: opts.maxClients ?? 32,
            recordDir: opts.recordDir ?? null,
            recordHashEveryTicks: opts.recordHashEveryTicks,
            budgetMsPerTick: WORKER_BUDGET_MS_PER_TICK,
            durability: opts.durability,
            checkpointEverySeconds: opts.checkpointEverySeconds,
          },
          scenarioModules: opts.workerScenarioModules,
          youngGenerationMb: opts.roomWorkerYoungGenerationMb,
          logLevel: logger.level,
          logger,
          moveCheckEveryMs: opts.roomMoveCheckEveryMs,
        });
  const factory = createRoomFactory({ scenarios, logger, recordDir: opts.recordDir ?? null, hashEveryTicks: opts.recordHashEveryTicks, durability: opts.durability, checkpointEverySeconds: opts.checkpointEverySeconds });
  let resumed: ResumeScan | null = null;
  const resumeDir = opts.resumeDir ?? null;
  const game = await GameServer.create({
    workers,
    factory,
    beforeDefaultRoom: async (server) => {
      if (resumeDir === null) return;
      resumed = await scanForResume(resumeDir, factory, logger);
      await reopenRooms(server, resumed, factory, logger);
    },
    onResumeTokenIssued: (room, playerId, key) => rememberResumeKey(room.recordingPath ?? factory.recordingPath(room.id), room.id, playerId, key, logger),
    defaultScenario: scenarioName,
    defaultParams: opts.params,
    seed: opts.seed,
    clock,
    metrics,
    logger,
    snapshotRateHz: opts.snapshotRateHz,
    netMode: opts.netMode,
    inputDelayTicks: opts.inputDelayTicks,
    maxClientsPerRoom: opts.maxClients,
    maxConnections: opts.maxConnections,
    maxRooms: opts.maxRooms,
    emptyRoomGraceMs: opts.emptyRoomGraceMs,
    limits: opts.limits,
    resumeGraceMs: opts.resumeGraceMs,
    seats: access.seats,
    requireSeat: access.requireSeat,
    directory: fleet ?? undefined,
  });

  const stockFiles = createStaticHandler(opts.clientDir ?? DEFAULT_CLIENT_DIR);
  const pageFiles = opts.pageDir === undefined ? null : createStaticHandler(opts.pageDir, true);
  const clientFiles = pageFiles === null ? stockFiles : async (req: IncomingMessage, res: ServerResponse) => (await pageFiles(req, res)) || stockFiles(req, res);
  const staticFiles = opts.replayFile ? withReplayLog(opts.replayFile, clientFiles) : clientFiles;
  const monitor = new ServerMonitor(game);
  const http = createHttpServer(
    createHttpApi({ game, scenarios, metrics, logger, access, staticFiles, monitor: createMonitorRoutes(monitor), fleet: fleet ?? undefined }),
    (error) => logger.error({ err: error }, 'HTTP request failed'),
    opts.tls,
  );
  const gateway = attachWsGateway(http, {
    clock,
    maxPayloadBytes: opts.limits?.maxMessageBytes ?? MAX_CLIENT_MESSAGE_BYTES,
    heartbeatMs: opts.heartbeatMs,
    closeGraceMs: opts.closeGraceMs,
    policy,
    tarpit,
    trustProxy: opts.trustProxy,
    metrics,
    logger,
    refuse: () => game.refusal(),
    checkUpgrade: access.checkUpgrade,
    onConnection: (conn) => {
      game.accept(conn);
    },
  });

  // The gate listens and hands admitted connections to the HTTP(S) server (which never listens itself).
  const gate = createTcpGate(http, { policy, tarpit, trustProxy: opts.trustProxy ?? false, metrics });
  try {
    await new Promise<void>((resolveListen, rejectListen) => {
      gate.once('error', rejectListen);
      gate.listen(port, host, () => {
        gate.off('error', rejectListen);
        // Node's HTTP server tracks its connections (headers/request timeouts, closeAllConnections) from its
        // 'listening' event; it is listening through the gate.
        http.emit('listening');
        resolveListen();
      });
    });
  } catch (error) {
    monitor.close();
    await game.close('failed to start');
    await gateway.close(0);
    await fleet?.close();
    const e = error as NodeJS.ErrnoException;
    throw new Error(e.code === 'EADDRINUSE' ? `port ${port} on ${host} is already in use (pick another with --port)` : `cannot listen on ${host}:${port}: ${e.message}`, { cause: error });
  }
  const address = gate.address() as AddressInfo;
  // Bound to every interface: show the loopback address, which a browser on this machine can open.
  const reachable = host === '0.0.0.0' ? '127.0.0.1' : host === '::' ? '::1' : host;
  const shownHost = reachable.includes(':') ? `[${reachable}]` : reachable;
  const secure = opts.tls !== undefined;
  const url = `${secure ? 'https' : 'http'}://${shownHost}:${address.port}/`;
  const wsUrl = `${secure ? 'wss' : 'ws'}://${shownHost}:${address.port}/`;
  logger.info({ url, scenario: scenarioName, snapshotRateHz: game.snapshotRateHz, recordDir: opts.recordDir ?? null, trustProxy: opts.trustProxy ?? false }, 'server listening');
  logAccess(logger, host, access);
  let closing: Promise<void> | null = null;
  let agones: AgonesLifecycle | null = null;
  let markClosed: () => void = () => undefined;
  const closed = new Promise<void>((resolve) => (markClosed = resolve));
  const running: RunningServer = {
    url,
    wsUrl,
    port: address.port,
    host,
    game,
    logger,
    policy,
    resumed,
    fleet,
    get agones() {
      return agones;
    },
    whenClosed: () => closed,
    close(reason = 'server shutting down') {
      closing ??= (async () => {
        monitor.close();
        await game.close(reason);
        await agones?.shutdown(reason);
        await fleet?.close();
        await gateway.close(1000);
        const stopped = new Promise<void>((done) => gate.close(() => done()));
        http.close(() => undefined); // stops its connection checks (it never listened itself, so it reports that)
        http.closeAllConnections();
        await stopped;
        logger.info({ reason }, 'server stopped');
        await flushLogger(logger);
        markClosed();
      })();
      return closing;
    },
  };
  try {
    agones = await joinFleet(
      { game, clock, logger, listenUrl: url, host, secure, maxRooms: opts.maxRooms ?? 6, closeServer: (reason) => void running.close(reason) },
      fleet,
      opts.fleet,
      opts.agones,
    );
  } catch (error) {
    await running.close('cannot start under Agones');
    throw error;
  }
  return running;
}
