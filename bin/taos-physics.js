#!/usr/bin/env node
// CLI entry: runs the CLI on Node 24 (from the TypeScript sources in a checkout, from dist/ in an installed package);
// re-executes with the pinned Node if needed.
import { spawnSync } from 'node:child_process';
import { existsSync } from 'node:fs';
import { createRequire, enableCompileCache } from 'node:module';

const major = Number(process.versions.node.split('.')[0]);
if (major < 24) {
  const require = createRequire(import.meta.url);
  let nodePath;
  try {
    nodePath = require.resolve('node/bin/node');
  } catch {
    console.error(`taos-physics needs Node >= 24 (found ${process.version}).`);
    process.exit(2);
  }
  const result = spawnSync(nodePath, [new URL(import.meta.url).pathname, ...process.argv.slice(2)], { stdio: 'inherit' });
  process.exit(result.status ?? 1);
}
// V8's code for the CLI's modules is kept on disk (NODE_COMPILE_CACHE, else a folder in the OS temp dir), which
// roughly halves module loading on every start after the first; room worker threads inherit it through the env.
// NODE_DISABLE_COMPILE_CACHE=1 turns it off.
const compileCache = enableCompileCache();
if (compileCache.directory) process.env.NODE_COMPILE_CACHE = compileCache.directory;
const source = new URL('../cli/main.ts', import.meta.url);
const { main } = await import(existsSync(source) ? source.href : new URL('../dist/cli/main.js', import.meta.url).href);
process.exitCode = await main(process.argv.slice(2));
