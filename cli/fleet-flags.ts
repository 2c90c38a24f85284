// The `serve` flags of a fleet: the Redis directory (--redis or TAOS_REDIS_URL, --public-url, --fleet-ttl,
// --fleet-prefix) and Agones (--agones or the sidecar's environment, --agones-single-session, --agones-drain), checked
// so that a mistake is a usage error (exit 2) before anything starts. docs/deploy.md says what they do.
import { AGONES_ENV, agonesSidecarPresent } from '../server/fleet/agones-lifecycle.ts';
import type { ParsedArgs } from './args.ts';
import { UsageError, type FlagSpec } from './command.ts';
import type { ServeOptions } from './serve.ts';

/** The environment variable that may hold --redis (its URL can carry a password). */
export const REDIS_URL_ENV = 'TAOS_REDIS_URL';

/** The flags, for the serve command's list. */
export const FLEET_FLAGS: readonly FlagSpec[] = [
  { name: 'redis', kind: 'string', valueName: 'URL', description: `join a fleet of servers through this Redis directory (or ${REDIS_URL_ENV}); default: one process` },
  { name: 'public-url', kind: 'string', valueName: 'URL', description: 'with --redis: where players reach this server (http:// or https://); default Agones\'s address, else the listening address' },
  { name: 'fleet-ttl', kind: 'int', valueName: 'SECONDS', description: 'with --redis: a silent server and its rooms leave the directory after this long; default 10', min: 1, max: 3600 },
  { name: 'fleet-prefix', kind: 'string', valueName: 'PREFIX', description: 'with --redis: prefix of every directory key (one Redis, several fleets); default taos:' },
  { name: 'agones', kind: 'boolean', description: `run as an Agones GameServer through the SDK sidecar (on by itself when ${AGONES_ENV[0]} is set)` },
  { name: 'agones-single-session', kind: 'boolean', description: 'with Agones: Allocate when the first player joins, Shutdown once the session is over' },
  { name: 'agones-drain', kind: 'int', valueName: 'SECONDS', description: 'with Agones: how long a finished session stays idle before Shutdown; default 5', min: 0, max: 3600 },
];

function isUrlOf(text: string, protocols: readonly string[]): boolean {
  try {
    return protocols.includes(new URL(text).protocol);
  } catch {
    return false;
  }
}

/** The directory options; undefined without --redis or TAOS_REDIS_URL (the flag wins; empty means unset). */
export function fleetOptions(args: ParsedArgs, env: NodeJS.ProcessEnv = process.env): ServeOptions['fleet'] {
  const fromEnv = env[REDIS_URL_ENV];
  const redisUrl = args.string('redis') ?? (fromEnv === undefined || fromEnv === '' ? null : fromEnv);
  if (redisUrl === null) {
    for (const flag of ['public-url', 'fleet-ttl', 'fleet-prefix']) if (args.has(flag)) throw new UsageError(`--${flag} needs --redis URL (or ${REDIS_URL_ENV})`);
    return undefined;
  }
  if (!isUrlOf(redisUrl, ['redis:', 'rediss:'])) throw new UsageError(`${args.has('redis') ? '--redis' : REDIS_URL_ENV} must be a redis:// or rediss:// URL`);
  const publicUrl = args.string('public-url');
  if (publicUrl !== undefined && !isUrlOf(publicUrl, ['http:', 'https:'])) throw new UsageError(`--public-url must be an http:// or https:// URL where players reach this server, got ${JSON.stringify(publicUrl)}`);
  const prefix = args.string('fleet-prefix');
  if (prefix !== undefined && !/^[A-Za-z0-9_.:-]{1,64}$/.test(prefix)) throw new UsageError('--fleet-prefix must be 1-64 characters of A-Z a-z 0-9 _ . : -');
  return { redisUrl, publicUrl, ttlSeconds: args.has('fleet-ttl') ? args.number('fleet-ttl') : undefined, prefix };
}

/** The Agones options: on with --agones or when the sidecar's environment is set; undefined otherwise. */
export function agonesOptions(args: ParsedArgs, env: NodeJS.ProcessEnv = process.env): ServeOptions['agones'] {
  if (!args.flag('agones') && !agonesSidecarPresent(env)) {
    for (const flag of ['agones-single-session', 'agones-drain']) if (args.has(flag)) throw new UsageError(`--${flag} needs --agones (or the Agones sidecar's ${AGONES_ENV.join('/')})`);
    return undefined;
  }
  return { singleSession: args.flag('agones-single-session'), drainSeconds: args.has('agones-drain') ? args.number('agones-drain') : undefined };
}
