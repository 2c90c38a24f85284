// Input-log throughput: encodes and writes a synthetic session (N players walking, turning, jumping, firing, a
// hash every tick), then streams it back; prints bytes per tick and MB/s. Run: node_modules/.bin/node bench/input-log.ts
import { mkdtemp, rm } from 'node:fs/promises';
import { tmpdir } from 'node:os';
import { join } from 'node:path';
import { LogReader } from '../server/log/log-reader.ts';
import { LogWriter } from '../server/log/log-writer.ts';
import type { TickInputRecord } from '../shared/sim/types.ts';

const ticks = Number(process.argv[2] ?? 216_000);
const playerCounts = [1, 4, 16];

function tickRecord(tick: number, players: number): TickInputRecord {
  const rec: TickInputRecord = { tick, leaves: [], joins: [], commands: [] };
  if (tick === 0) for (let p = 1; p <= players; p++) rec.joins.push({ playerId: p, name: `bot-${p}` });
  for (let p = 1; p <= players; p++) {
    const phase = ((tick >> 6) + p) % 4;
    rec.commands.push({
      playerId: p,
      input: { moveX: phase === 0 ? 0 : 90, moveZ: phase === 3 ? 0 : -127, yaw: (tick * 37 + p * 4000) % 65536, pitch: 0, buttons: tick % 45 === p % 45 ? 1 : tick % 20 === 0 ? 2 : 0 },
    });
  }
  return rec;
}

const hash = (t: number): string => ((t * 2654435761) >>> 0).toString(16).padStart(8, '0') + (t >>> 0).toString(16).padStart(8, '0');

const dir = await mkdtemp(join(tmpdir(), 'taos-log-bench-'));
try {
  for (const players of playerCounts) {
    const path = join(dir, `p${players}.taoslog`);
    const records = Array.from({ length: 600 }, (_, i) => tickRecord(i, players));
    let start = performance.now();
    const w = await LogWriter.create(path, { joltVersion: '1.1.0', scenario: 'bench', params: {}, seed: 1, tickRateHz: 60, hashEveryTicks: 1, checkpointEveryTicks: 0, createdBy: 'bench' });
    w.appendHash(0, hash(0));
    for (let t = 0; t < ticks; t++) {
      const r = records[t % 600];
      r.tick = t;
      w.appendTick(r);
      w.appendHash(t + 1, hash(t + 1));
      if (t % 600 === 599) await w.settled(); // a live session yields to the event loop between ticks
    }
    await w.close(ticks, hash(ticks));
    const writeMs = performance.now() - start;
    start = performance.now();
    const reader = await LogReader.open(path);
    let n = 0;
    for await (const e of reader.entries()) if (e.type === 'tick') n++;
    await reader.close();
    const readMs = performance.now() - start;
    const mb = w.bytesWritten / 1e6;
    console.log(
      `${players} players, ${ticks} ticks: ${(w.bytesWritten / ticks).toFixed(1)} bytes/tick (hash every tick), ${mb.toFixed(1)} MB; ` +
        `write ${(mb / (writeMs / 1000)).toFixed(1)} MB/s (${((writeMs * 1000) / ticks).toFixed(2)} µs/tick), ` +
        `read ${(mb / (readMs / 1000)).toFixed(1)} MB/s (${((readMs * 1000) / n).toFixed(2)} µs/tick)`,
    );
  }
} finally {
  await rm(dir, { recursive: true, force: true });
}
