// `serve [--port 8080] [--host 127.0.0.1] [--scenario NAME] [--param k=v] [--snapshot-rate 30] [--net-mode auto] [--input-delay-ticks 0] [--record DIR]
// [--max-clients N] [--tls-cert FILE --tls-key FILE] [--trust-proxy] [--replay FILE] [access flags] …`: runs the networked server
// (HTTP(S) + WebSocket on one port) until SIGINT/SIGTERM. Secrets may come from the environment (TAOS_ADMIN_TOKEN,
// TAOS_JOIN_SECRET) so they stay out of `ps` output.
import { readFileSync, statSync } from 'node:fs';
import { availableParallelism } from 'node:os';
import { DEFAULT_SCENARIO } from '../scenarios/index.ts';
import { ADMIN_TOKEN_ENV, checkAdminTokenText } from '../server/access/admin-auth.ts';
import { parseAllowedOrigins } from '../server/access/origin-policy.ts';
import { JOIN_SECRET_ENV, MIN_JOIN_SECRET_LENGTH } from '../server/access/seat-tokens.ts';
import type { ConnectionPolicyOptions } from '../server/connection-policy.ts';
import { isNetModeRequest, type NetModeRequest } from '../server/net-mode-policy.ts';
import { DEFAULT_CHECKPOINT_EVERY_SECONDS, DEFAULT_DURABILITY, DEFAULT_DURABILITY_INTERVAL_MS, DURABILITY_MODES, type DurabilityMode } from '../server/recorder.ts';
import { MAX_INPUT_DELAY_TICKS } from '../shared/protocol/limits.ts';
import { TICK_RATE_HZ } from '../shared/tick-rate.ts';
import { LogFormat } from '../server/pretty-log.ts';
import { agonesOptions, FLEET_FLAGS, fleetOptions } from './fleet-flags.ts';
import { runServe, type ServeOptions } from './serve.ts';
import type { ParsedArgs } from './args.ts';
import { UsageError, type CliIo, type CommandSpec } from './command.ts';
import { resolve as resolvePath } from 'node:path';
import { pathToFileURL } from 'node:url';
import { scenarioSource } from '../server/create-server.ts';
import { isScenarioPath } from '../server/scenario-module.ts';
import { checkParams, parseSeed, scenarioFromArg } from './scenario-setup.ts';

const LOG_LEVELS = ['trace', 'debug', 'info', 'warn', 'error', 'fatal', 'silent'];

/** The PEM files of --tls-cert and --tls-key (both or neither), read now so a typo is a usage error. */
function readTls(certPath: string | undefined, keyPath: string | undefined): { cert: Buffer; key: Buffer } | undefined {
  if (certPath === undefined && keyPath === undefined) return undefined;
  if (certPath === undefined || keyPath === undefined) throw new UsageError('--tls-cert and --tls-key go together: give both (PEM files) or neither');
  const read = (flag: string, path: string): Buffer => {
    try {
      return readFileSync(path);
    } catch (error) {
      throw new UsageError(`cannot read ${flag} ${path}: ${(error as NodeJS.ErrnoException).code ?? (error as Error).message}`);
    }
  };
  return { cert: read('--tls-cert', certPath), key: read('--tls-key', keyPath) };
}

/** A secret from its flag, else from its environment variable (empty means unset); null when neither is set. */
function secret(args: ParsedArgs, flag: string, env: string): string | null {
  const given = args.string(flag);
  if (given !== undefined) return given;
  const fromEnv = process.env[env];
  return fromEnv === undefined || fromEnv === '' ? null : fromEnv;
}

/** The access flags, checked so that a mistake is a usage error (exit 2) before anything starts. */
function accessOptions(args: ParsedArgs): Pick<ServeOptions, 'allowedOrigins' | 'adminToken' | 'joinSecret' | 'requireSeat' | 'seatTtlMs' | 'resumeGraceMs'> {
  const allowedOrigins = args.string('allowed-origins');
  const adminToken = secret(args, 'admin-token', ADMIN_TOKEN_ENV);
  const joinSecret = secret(args, 'join-secret', JOIN_SECRET_ENV);
  try {
    parseAllowedOrigins(allowedOrigins);
    if (adminToken !== null) checkAdminTokenText(adminToken, args.has('admin-token') ? '--admin-token' : ADMIN_TOKEN_ENV);
  } catch (error) {
    throw new UsageError((error as Error).message);
  }
  if (joinSecret !== null && joinSecret.length < MIN_JOIN_SECRET_LENGTH) {
    throw new UsageError(`${args.has('join-secret') ? '--join-secret' : JOIN_SECRET_ENV} must be at least ${MIN_JOIN_SECRET_LENGTH} characters`);
  }
  const requireSeat = args.flag('require-seat');
  if (requireSeat && adminToken === null) throw new UsageError(`--require-seat needs an admin token (--admin-token or ${ADMIN_TOKEN_ENV}): otherwise anyone could reserve a seat`);
  return {
    allowedOrigins,
    adminToken,
    joinSecret,
    requireSeat,
    seatTtlMs: args.number('seat-ttl', 60) * 1000,
    resumeGraceMs: args.number('resume-grace', 30) * 1000,
  };
}

function netModeFlag(value: string | undefined): NetModeRequest | undefined {
  if (value === undefined) return undefined;
  if (!isNetModeRequest(value)) throw new UsageError(`--net-mode must be snapshot, predict or auto, got "${value}"`);
  return value;
}

/** The port from the PORT environment variable (what hosting platforms set), else 8080; a bad value is a usage error. */
export function portFromEnv(env: string | undefined): number {
  if (env === undefined || env === '') return 8080;
  const port = Number(env);
  if (!/^\d+$/.test(env) || port > 65535) throw new UsageError(`PORT must be a TCP port (0-65535), got "${env}"`);
  return port;
}

/** --durability, --durability-interval-ms and --checkpoint-every, checked. */
function recordingOptions(args: ParsedArgs): Pick<ServeOptions, 'durability' | 'checkpointEverySeconds' | 'resumeDir' | 'recordDir' | 'recordHashEveryTicks'> {
  const record = args.string('record');
  if (record === '') throw new UsageError('--record must name a directory');
  const resume = args.string('resume');
  if (resume === '') throw new UsageError('--resume must name a directory');
  const mode = args.string('durability') ?? DEFAULT_DURABILITY;
  if (!(DURABILITY_MODES as readonly string[]).includes(mode)) throw new UsageError(`--durability must be one of ${DURABILITY_MODES.join(', ')}, got "${mode}"`);
  if (args.has('durability-interval-ms') && mode !== 'interval') throw new UsageError('--durability-interval-ms goes with --durability interval');
  return {
    durability: { mode: mode as DurabilityMode, intervalMs: args.number('durability-interval-ms', DEFAULT_DURABILITY_INTERVAL_MS) },
    checkpointEverySeconds: args.number('checkpoint-every', DEFAULT_CHECKPOINT_EVERY_SECONDS),
    // Resumed rooms go on in their own logs; new rooms are recorded beside them unless --record says elsewhere.
    recordDir: record ?? resume ?? null,
    resumeDir: resume ?? null,
    recordHashEveryTicks: args.number('hash-every'),
  };
}

async function run(args: ParsedArgs, io: CliIo): Promise<number> {
  const scenario = args.string('scenario') ?? DEFAULT_SCENARIO;
  const def = await scenarioFromArg(scenario);
  // A game's own module: its scenario is the only one the server offers.
  // Room workers import that module themselves: a definition holds functions and cannot be handed to a thread.
  const own = isScenarioPath(scenario) ? { scenarios: scenarioSource([def]), workerScenarioModules: [pathToFileURL(resolvePath(scenario)).href] } : {};
  const params = args.pairs('param');
  checkParams(def, params);
  const pageDir = args.string('page');
  if (pageDir !== undefined && !statSync(pageDir, { throwIfNoEntry: false })?.isDirectory()) throw new UsageError(`--page ${pageDir} is not a folder`);
  const logLevel = args.string('log-level');
  if (logLevel !== undefined && !LOG_LEVELS.includes(logLevel)) throw new UsageError(`--log-level must be one of ${LOG_LEVELS.join(', ')}, got "${logLevel}"`);
  const logFormat = args.string('log-format');
  if (logFormat !== undefined && logFormat !== LogFormat.Json && logFormat !== LogFormat.Pretty) throw new UsageError(`--log-format must be json or pretty, got "${logFormat}"`);
  const host = args.string('host') ?? '127.0.0.1';
  if (host === '') throw new UsageError('--host must not be empty');
  const connectionPolicy: Partial<ConnectionPolicyOptions> = {};
  if (args.has('max-connections-per-address')) connectionPolicy.maxSocketsPerAddress = args.number('max-connections-per-address');
  if (args.has('max-pending-per-address')) connectionPolicy.maxPendingPerAddress = args.number('max-pending-per-address');
  return runServe(
    {
      port: args.has('port') ? args.number('port') : portFromEnv(process.env.PORT),
      host,
      scenario: def.name,
      ...own,
      params,
      seed: parseSeed(args.string('seed')),
      snapshotRateHz: args.number('snapshot-rate', 30),
      netMode: netModeFlag(args.string('net-mode')),
      inputDelayTicks: args.number('input-delay-ticks', 0),
      maxClients: args.number('max-clients', 32),
      maxRooms: args.number('max-rooms'),
      roomWorkers: args.number('room-workers', availableParallelism()),
      maxConnections: args.number('max-connections'),
      connectionPolicy,
      limits: args.has('hello-timeout-ms') ? { helloTimeoutMs: args.number('hello-timeout-ms') } : undefined,
      trustProxy: args.flag('trust-proxy'),
      tls: readTls(args.string('tls-cert'), args.string('tls-key')),
      clientDir: args.string('client-dir'),
      replayFile: args.string('replay'),
      pageDir,
      logLevel,
      logFormat,
      ...recordingOptions(args),
      fleet: fleetOptions(args),
      agones: agonesOptions(args),
      ...accessOptions(args),
    },
    io,
  );
}

/** The serve command. */
export const serveCommand: CommandSpec = {
  name: 'serve',
  summary: 'Run the multiplayer server (HTTP + WebSocket on one port)',
  details:
    'Serves the browser client at /, WebSocket play on the same port, /healthz, /metrics (Prometheus) and\n' +
    '/api/rooms. The default room runs --scenario; a client may open another room by naming a scenario as its room.\n' +
    'With --record DIR every room writes its input log there (replay it with `replay FILE`, or in the browser at\n' +
    '/replay, where --replay FILE serves one), with a checkpoint every\n' +
    `--checkpoint-every seconds. --durability (default ${DEFAULT_DURABILITY}): "tick" writes and fdatasyncs each tick's record (group\n` +
    'commit) before its snapshot, events or input acks leave, so a crash loses nothing any client saw, for the\n' +
    "disk's sync latency added to each tick's delivery (docs/server.md); \"interval\" syncs every\n" +
    '--durability-interval-ms and holds nothing back (a crash loses at most that much); "off" hands records to the OS\n' +
    'every second.\n' +
    'With --resume DIR every unterminated log in DIR is checked (CRC, hashes), re-simulated from its last checkpoint\n' +
    'and its room reopened under the same id at its last durable tick, appending to the same log; its players get\n' +
    '--resume-grace to come back. A log that fails a check is named with the record and left alone. Logs go to stderr:\n' +
    'readable lines on a terminal, JSON lines when piped (or with --log-format json). SIGINT/SIGTERM: clients are\n' +
    'told why, recordings get a last checkpoint and their end record, then the process exits.\n' +
    `Access control (docs/server.md): pages from other origins are refused; ${ADMIN_TOKEN_ENV} and ${JOIN_SECRET_ENV} may\n` +
    'replace --admin-token and --join-secret (the flag wins).',
  positionals: [],
  flags: [
    { name: 'port', kind: 'int', valueName: 'PORT', description: 'TCP port (0: any free port); default the PORT environment variable, else 8080', min: 0, max: 65535 },
    { name: 'host', kind: 'string', valueName: 'HOST', description: 'interface to bind; default 127.0.0.1' },
    { name: 'scenario', kind: 'string', valueName: 'NAME|FILE', description: `scenario of the default room: a built-in name or a module file (then the only one offered); default ${DEFAULT_SCENARIO}` },
    { name: 'param', kind: 'pair', valueName: 'k=v', description: 'scenario parameter (repeatable)' },
    { name: 'seed', kind: 'string', valueName: 'SEED', description: 'simulation seed of every room; default 1' },
    { name: 'snapshot-rate', kind: 'int', valueName: 'HZ', description: `snapshots per second per client (1-${TICK_RATE_HZ}); default 30`, min: 1, max: TICK_RATE_HZ },
    { name: 'net-mode', kind: 'string', valueName: 'MODE', description: 'how rooms serve clients: snapshot, predict, or auto (predict where a frame affords the rollback); default auto' },
    { name: 'input-delay-ticks', kind: 'int', valueName: 'N', description: `input delay predict rooms announce: own commands apply N ticks after they are made (0-${MAX_INPUT_DELAY_TICKS}); default 0`, min: 0, max: MAX_INPUT_DELAY_TICKS },
    { name: 'record', kind: 'string', valueName: 'DIR', description: "write every room's input log into DIR" },
    { name: 'durability', kind: 'string', valueName: 'MODE', description: `when recorded ticks reach the disk: tick, interval or off; default ${DEFAULT_DURABILITY}` },
    { name: 'durability-interval-ms', kind: 'int', valueName: 'MS', description: `sync period of --durability interval; default ${DEFAULT_DURABILITY_INTERVAL_MS}`, min: 1, max: 60_000 },
    { name: 'hash-every', kind: 'int', valueName: 'N', description: 'a state hash in recordings every N ticks; default 60', min: 1, max: 3600 },
    { name: 'resume', kind: 'string', valueName: 'DIR', description: 'first reopen the room of every interrupted recording in DIR at its last durable tick (implies --record DIR)' },
    { name: 'checkpoint-every', kind: 'int', valueName: 'SECONDS', description: `a checkpoint in recordings every SECONDS of play (0: none); default ${DEFAULT_CHECKPOINT_EVERY_SECONDS}`, min: 0, max: 86_400 },
    { name: 'max-clients', kind: 'int', valueName: 'N', description: 'most clients per room; default 32', min: 1, max: 1000 },
    { name: 'max-rooms', kind: 'int', valueName: 'N', description: 'most rooms at once (each is a Jolt world in the 128 MB heap); default 6', min: 1, max: 32 },
    { name: 'room-workers', kind: 'int', valueName: 'N', description: "worker threads that run the rooms (0: every room on the main thread); default the machine's cores", min: 0, max: 256 },
    { name: 'max-connections', kind: 'int', valueName: 'N', description: 'most WebSocket connections in all; default 256', min: 1, max: 100_000 },
    { name: 'max-connections-per-address', kind: 'int', valueName: 'N', description: 'most WebSocket connections from one address (IPv6: one /64); default 32', min: 1, max: 100_000 },
    { name: 'max-pending-per-address', kind: 'int', valueName: 'N', description: 'most connections from one address that have not said hello yet; default 8', min: 1, max: 100_000 },
    { name: 'hello-timeout-ms', kind: 'int', valueName: 'MS', description: 'time a new connection has to say hello; default 5000', min: 100, max: 600_000 },
    { name: 'tls-cert', kind: 'string', valueName: 'FILE', description: 'serve HTTPS and WSS with this PEM certificate (chain); needs --tls-key' },
    { name: 'tls-key', kind: 'string', valueName: 'FILE', description: "the certificate's PEM private key" },
    { name: 'trust-proxy', kind: 'boolean', description: 'take client addresses from X-Forwarded-For/-Proto (only behind a reverse proxy)' },
    { name: 'client-dir', kind: 'string', valueName: 'DIR', description: 'built browser client to serve; default dist/client' },
    { name: 'replay', kind: 'string', valueName: 'FILE', description: 'an input log the replay viewer at /replay opens (served at /replay.taoslog)' },
    { name: 'page', kind: 'string', valueName: 'DIR', description: "a game's own page folder, served before the built client (/kit.js stays reachable)" },
    { name: 'log-level', kind: 'string', valueName: 'LEVEL', description: 'log level (trace, debug, info, warn, error, silent); default info' },
    { name: 'log-format', kind: 'string', valueName: 'FORMAT', description: 'log lines on stderr: pretty (time, level, message, fields) or json; default pretty on a terminal, else json' },
    { name: 'allowed-origins', kind: 'string', valueName: 'LIST', description: 'comma-separated origins whose pages may connect or post (plus self, loopback, *); default self,loopback' },
    { name: 'admin-token', kind: 'string', valueName: 'TOKEN', description: `bearer token required for POST/DELETE /api/... and /metrics (or ${ADMIN_TOKEN_ENV}); default none` },
    { name: 'join-secret', kind: 'string', valueName: 'SECRET', description: `HMAC key of seat tokens, shared by servers that accept each other's seats (or ${JOIN_SECRET_ENV}); default random` },
    { name: 'require-seat', kind: 'boolean', description: 'admit only players whose hello carries a seat token (needs an admin token)' },
    { name: 'seat-ttl', kind: 'int', valueName: 'SECONDS', description: 'lifetime of a seat token; default 60', min: 1, max: 3600 },
    ...FLEET_FLAGS,
    { name: 'resume-grace', kind: 'int', valueName: 'SECONDS', description: 'how long a dropped player is held for a reconnect (0: off); default 30', min: 0, max: 3600 },
  ],
  run,
};
