// Property test of canonical inputs through the real server on loopback: two players send raw msgpack input frames
// full of −0, fractions that round to ±0, out-of-range and huge values; the room records with a hash every tick,
// and the recording replays with every one of those hashes matching (the live step and the log saw one value).
import { mkdtempSync, readdirSync, readFileSync, rmSync } from 'node:fs';
import { tmpdir } from 'node:os';
import { join } from 'node:path';
import { afterAll, describe, expect, it } from 'vitest';
import { replayLog } from '../../cli/replay-session.ts';
import { readLogBytes } from '../../server/log/log-bytes.ts';
import { silentLogger } from '../../server/logger.ts';
import { createMetrics } from '../../server/metrics.ts';
import { startServer } from '../../server/start-server.ts';
import { ClientOpcode } from '../../shared/protocol/index.ts';
import { Prng } from '../../shared/sim/prng.ts';
import { MsgpackWriter } from '../helpers/msgpack-writer.ts';
import { writeNumber } from '../helpers/hostile-frames.ts';
import { WsTestClient } from './ws-client.ts';

const tmp = mkdtempSync(join(tmpdir(), 'taos-canonical-'));
afterAll(() => rmSync(tmp, { recursive: true, force: true }));

/** A raw value for one command field: mostly ones that round to ±0, fractions, or lie far out of range. */
function rawField(rng: Prng, steps: number): number {
  switch (rng.int(0, 7)) {
    case 0:
      return -0;
    case 1:
      return -rng.next() * 0.5; // rounds to −0 under Math.round
    case 2:
      return rng.range(-1, 1);
    case 3:
      return rng.range(-1.2, 1.2) * steps;
    case 4:
      return rng.pick([1e300, -1e300, 2 ** 53 + 2, -(2 ** 40), 1e15]);
    case 5:
      return rng.int(-steps, steps) + rng.pick([0.5, -0.5, 0.49, -0.49]);
    default:
      return rng.int(-steps, steps);
  }
}

/** An input frame for `count` ticks from `firstTick`, each field written as a float (−0 keeps its sign on the wire). */
function rawInput(rng: Prng, firstTick: number, count: number): Uint8Array {
  const w = new MsgpackWriter().arrayHeader(3).int(ClientOpcode.Input, 'fix').int(firstTick, 'u32').arrayHeader(count);
  for (let i = 0; i < count; i++) {
    w.arrayHeader(5);
    w.f64(rawField(rng, 127)).f64(rawField(rng, 127));
    writeNumber(w, rng, rawField(rng, 65536));
    w.f64(rawField(rng, 16384));
    writeNumber(w, rng, rng.pick([0, 1, 2, 4, 8, 15, 16, 255, 2 ** 31, 2 ** 40 + 3]));
  }
  return w.finish();
}

describe('canonical inputs (real server)', () => {
  it('replays a session of −0, fractional and out-of-range inputs with every per-tick hash matching', async () => {
    const dir = join(tmp, 'rec');
    const metrics = createMetrics({ processMetrics: false });
    const server = await startServer({ port: 0, scenario: 'character-course', params: { crateRows: 1 }, recordDir: dir, recordHashEveryTicks: 1, logger: silentLogger(), metrics, clientDir: join(tmp, 'no-client') });
    const seed = Number(process.env.CANONICAL_SEED ?? 0x0c0ffee);
    const rng = new Prng(seed);
    let ticksRecorded = 0;
    try {
      const players = [await WsTestClient.join(server.wsUrl, 'ann'), await WsTestClient.join(server.wsUrl, 'bob')];
      const room = server.game.rooms.local('default')!;
      const start = room.sim.tick;
      while (room.sim.tick < start + 300) {
        for (const p of players) p.sendRaw(rawInput(rng, room.sim.tick + 2, rng.int(1, 4)));
        await new Promise((r) => setTimeout(r, 8));
      }
      for (const p of players) {
        expect(p.closed, 'a player was disconnected').toBeNull();
        expect(p.ofType('error')).toEqual([]);
      }
      ticksRecorded = room.sim.tick;
    } finally {
      await server.close('test over');
    }
    const [file] = readdirSync(dir).filter((f) => f.endsWith('.taoslog')); // resume keys sit beside each log
    const report = await replayLog(join(dir, file));
    expect(report.status, `seed ${seed}: ${JSON.stringify(report.divergence)}`).toBe('ok');
    expect(report.log).toBe('complete');
    expect(report.ticks).toBeGreaterThanOrEqual(ticksRecorded);
    expect(report.hashesChecked).toBe(report.ticks + 2); // a hash record after every tick (and at tick 0), and the end record
    // The inputs were applied, clamped where out of range, and every recorded command is canonical.
    const { entries } = readLogBytes(new Uint8Array(readFileSync(join(dir, file))));
    const commands = entries.flatMap((e) => (e.type === 'tick' ? e.record.commands.map((c) => c.input) : []));
    expect(commands.filter((c) => c.moveX !== 0 || c.moveZ !== 0).length).toBeGreaterThan(100);
    expect(commands.every((c) => Object.values(c).every((v) => Number.isInteger(v) && !Object.is(v, -0)))).toBe(true);
    expect(await metrics.registry.getSingleMetricAsString('taos_inputs_clamped_total')).toMatch(/ [1-9]\d*$/);
  });
});
