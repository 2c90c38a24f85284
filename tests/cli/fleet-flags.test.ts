// Tests for the serve command's fleet and Agones flags (cli/fleet-flags.ts): mistakes are usage errors (exit 2)
// found before anything starts, and the environment turns them on the way the docs say.
import { describe, expect, it } from 'vitest';
import { parseArgs } from '../../cli/args.ts';
import { agonesOptions, fleetOptions } from '../../cli/fleet-flags.ts';
import { serveCommand } from '../../cli/serve-command.ts';
import { cli } from '../helpers/cli.ts';

const args = (...argv: string[]) => parseArgs(serveCommand, argv);

describe('fleet flags', () => {
  it('refuses fleet and Agones options without --redis or --agones, and malformed URLs and prefixes', async () => {
    for (const [argv, message] of [
      [['--public-url', 'http://10.0.0.7:8080/'], /--public-url needs --redis URL \(or TAOS_REDIS_URL\)/],
      [['--fleet-ttl', '5'], /--fleet-ttl needs --redis/],
      [['--redis', 'http://127.0.0.1:6379'], /--redis must be a redis:\/\/ or rediss:\/\/ URL/],
      [['--redis', 'redis://127.0.0.1:6379', '--public-url', 'ws://10.0.0.7/'], /--public-url must be an http:\/\/ or https:\/\/ URL/],
      [['--redis', 'redis://127.0.0.1:6379', '--fleet-prefix', 'a b'], /--fleet-prefix must be 1-64 characters/],
      [['--agones-drain', '3'], /--agones-drain needs --agones/],
    ] as const) {
      const r = await cli('serve', ...argv);
      expect(r.code).toBe(2);
      expect(r.stderr).toMatch(message);
    }
  });

  it('reads the Redis URL from TAOS_REDIS_URL when --redis is not given, and the flag wins', () => {
    const env = { TAOS_REDIS_URL: 'redis://:secret@redis:6379' };
    expect(fleetOptions(args(), env)).toEqual({ redisUrl: 'redis://:secret@redis:6379', publicUrl: undefined, ttlSeconds: undefined, prefix: undefined });
    expect(fleetOptions(args('--redis', 'redis://other:6380', '--fleet-ttl', '4', '--fleet-prefix', 'game2:'), env)).toEqual({ redisUrl: 'redis://other:6380', publicUrl: undefined, ttlSeconds: 4, prefix: 'game2:' });
    expect(fleetOptions(args(), { TAOS_REDIS_URL: '' })).toBeUndefined();
  });

  it('turns Agones on with --agones or the sidecar\'s environment only', () => {
    expect(agonesOptions(args(), {})).toBeUndefined();
    expect(agonesOptions(args(), { AGONES_SDK_GRPC_PORT: '9357' })).toEqual({ singleSession: false, drainSeconds: undefined });
    expect(agonesOptions(args('--agones', '--agones-single-session', '--agones-drain', '0'), {})).toEqual({ singleSession: true, drainSeconds: 0 });
  });
});
