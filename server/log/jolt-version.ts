// The installed jolt-physics version, read from its package.json: stamped into every input log so a replay can
// warn when it runs on a different physics build than the recording did.
import { readFileSync } from 'node:fs';
import { createRequire } from 'node:module';
import { dirname, join } from 'node:path';

let cached: string | null = null;

/** Version string of the jolt-physics package this process loads (e.g. "1.1.0"). */
export function installedJoltVersion(): string {
  if (cached !== null) return cached;
  const require = createRequire(import.meta.url);
  const entry = require.resolve('jolt-physics'); // <pkg>/dist/<file>.js
  const pkg = JSON.parse(readFileSync(join(dirname(dirname(entry)), 'package.json'), 'utf8')) as { name?: string; version?: unknown };
  if (pkg.name !== 'jolt-physics' || typeof pkg.version !== 'string') throw new Error(`cannot read the jolt-physics version near ${entry}`);
  cached = pkg.version;
  return cached;
}
