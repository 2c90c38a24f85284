// The start-up figure's probe: a fresh process that starts the server the way `serve` does and reports where the time
// went, from process start (performance.now() counts from it): Node's own boot, loading the server's modules, loading
// Jolt's WASM, and startServer (the default room's build and listening). Prints one JSON line, then shuts down.
// The compile cache is on as in bin/taos-physics.js (the figure points NODE_COMPILE_CACHE at its own folder).
// Run: node bench/procs/startup-probe.ts SCENARIO
import { enableCompileCache } from 'node:module';

const bootMs = performance.now();
enableCompileCache();
const { startServer } = await import('../../server/start-server.ts');
const { silentLogger } = await import('../../server/logger.ts');
const { loadJoltNode } = await import('../../server/physics-node.ts');
const importedMs = performance.now();
await loadJoltNode();
const joltMs = performance.now();
const server = await startServer({ port: 0, scenario: process.argv[2], logger: silentLogger() });
const listeningMs = performance.now();
process.stdout.write(`${JSON.stringify({ probe: { bootMs, importMs: importedMs - bootMs, joltMs: joltMs - importedMs, startServerMs: listeningMs - joltMs, totalMs: listeningMs } })}\n`);
await server.close('probe done');
