// Child process of the room-churn test: a loopback server opens and closes rooms (every other one with two WebSocket
// players; closed by Room.close, so the probe runs on any tree) and prints external memory and RSS after full GCs.
// Run: node --expose-gc [--max-semi-space-size=4] tests/server/room-churn-probe.ts [--cycles 50] [--warmup 15]
import { silentLogger } from '../../server/logger.ts';
import { createMetrics } from '../../server/metrics.ts';
import { startServer } from '../../server/start-server.ts';
import { WsTestClient } from './ws-client.ts';

function arg(name: string, fallback: string): string {
  const i = process.argv.indexOf(`--${name}`);
  return i >= 0 && i + 1 < process.argv.length ? process.argv[i + 1] : fallback;
}

const cycles = Number(arg('cycles', '50'));
const warmup = Number(arg('warmup', '15'));
const scenario = arg('scenario', 'character-course');
const gc = (globalThis as { gc?: () => void }).gc;
if (!gc) throw new Error('room-churn-probe: run with node --expose-gc');

interface Memory {
  externalBytes: number;
  rssBytes: number;
  arrayBuffersBytes: number;
  heapUsedBytes: number;
  heapTotalBytes: number;
}

/**
 * Memory once GC has run to a fixed point. A collected WASM memory leaves external memory only when V8's concurrent
 * sweeper frees its backing store, which a loaded machine delays: collect until external memory holds still for
 * three readings (at most ~10 s), and take the least RSS of those, so a page not yet handed back does not count.
 */
async function settledMemory(): Promise<Memory> {
  const readings: Memory[] = [];
  for (let i = 0; i < 100; i++) {
    gc!();
    await new Promise((r) => setTimeout(r, 100));
    const m = process.memoryUsage();
    readings.push({ externalBytes: m.external, rssBytes: m.rss, arrayBuffersBytes: m.arrayBuffers, heapUsedBytes: m.heapUsed, heapTotalBytes: m.heapTotal });
    const last = readings.slice(-3);
    if (last.length === 3 && last.every((r) => r.externalBytes === last[0].externalBytes)) break;
  }
  const stable = readings.slice(-3);
  return stable.reduce((best, r) => (r.rssBytes < best.rssBytes ? r : best));
}

const server = await startServer({ port: 0, host: '127.0.0.1', scenario, logger: silentLogger(), metrics: createMetrics({ processMetrics: false }), maxRooms: 4 });

async function cycle(i: number): Promise<void> {
  const id = `churn-${i}`;
  const room = await server.game.rooms.create(id, scenario, {});
  const players: WsTestClient[] = [];
  if (i % 2 === 1) {
    for (let p = 0; p < 2; p++) players.push(await WsTestClient.join(server.wsUrl, `p${p}`, id));
    for (const c of players) await c.waitFor(() => c.frames.length >= 3, 10_000, 'three snapshots');
  }
  await room.close(`churn cycle ${i}`);
  for (const c of players) await c.waitFor(() => c.closed !== null, 10_000, 'the room-closed bye');
}

let n = 0;
for (; n < warmup; n++) await cycle(n);
const before = await settledMemory();
const trace: Array<Memory & { cycle: number }> = [];
for (let k = 0; k < cycles; k++, n++) {
  await cycle(n);
  if ((k + 1) % 5 === 0) {
    const m = await settledMemory();
    trace.push({ cycle: k + 1, ...m });
  }
}
const after = await settledMemory();
await server.close('probe done');
process.stdout.write(`${JSON.stringify({ cycles, warmup, scenario, before, after, trace })}\n`);
