// Fleet tests' Redis: a describe block that skips with a message when redis-server is missing outside CI and fails
// under CI=true, and the throw-away redis-server itself (tests/helpers/redis-process.ts).
import { describe, it } from 'vitest';
import { redisMissingReason } from './redis-process.ts';

export { freePort, redisMissingReason, startRedisServer, type RedisServer } from './redis-process.ts';

/** A describe block that needs redis-server: skipped with a message without it, a failure under CI=true. */
export function describeRedis(name: string, body: () => void): void {
  const missing = redisMissingReason();
  if (!missing) {
    describe(name, body);
    return;
  }
  if (process.env.CI === 'true') {
    describe(name, () => {
      it('needs redis-server', () => {
        throw new Error(`fleet tests cannot run: ${missing}; CI=true, so this is a failure, not a skip`);
      });
    });
    return;
  }
  console.warn(`[fleet tests skipped] ${name}: ${missing}`);
  describe.skip(name, body);
}

