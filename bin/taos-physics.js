#!/usr/bin/env node
// CLI entry: runs cli/main.ts on Node 24 (TypeScript type stripping); re-executes with the pinned Node if needed.
import { spawnSync } from 'node:child_process';
import { createRequire } from 'node:module';

const major = Number(process.versions.node.split('.')[0]);
if (major < 24) {
  const require = createRequire(import.meta.url);
  let nodePath;
  try {
    nodePath = require.resolve('node/bin/node');
  } catch {
    console.error(`taos-physics needs Node >= 24 (found ${process.version}); run "npm install" to get the pinned one.`);
    process.exit(2);
  }
  const result = spawnSync(nodePath, [new URL(import.meta.url).pathname, ...process.argv.slice(2)], { stdio: 'inherit' });
  process.exit(result.status ?? 1);
}
const { main } = await import('../cli/main.ts');
process.exitCode = await main(process.argv.slice(2));
