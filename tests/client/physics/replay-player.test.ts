// Tests of client/physics/replay-player.ts (run in Node; the browser runs the same code): one pass checks every
// recorded hash and names the first tick that differs, seeking forward and back lands on the state of that tick,
// and a record the simulation cannot apply stops playback before it with the reason.
import { afterEach, describe, expect, it } from 'vitest';
import '../../../server/physics-node.ts';
import { ReplayPlayer } from '../../../client/physics/replay-player.ts';
import { getScenario } from '../../../scenarios/index.ts';
import { LogEncoder } from '../../../server/log/log-encoder.ts';
import { BotScript } from '../../../shared/sim/bots.ts';
import { Simulation } from '../../../shared/sim/simulation.ts';
import type { TickInputRecord } from '../../../shared/sim/types.ts';

const HEADER = { joltVersion: '1.1.0', scenario: 'shape-rain', params: { count: 30 }, seed: 5, tickRateHz: 60, hashEveryTicks: 20, checkpointEveryTicks: 0, createdBy: 'tests' };

/** A 200-tick shape-rain session with two bots; `hashAt` may doctor the recorded hash of a tick. */
async function session(opts: { hashAt?: (tick: number, hash: string) => string; records?: (r: TickInputRecord) => TickInputRecord } = {}): Promise<{ bytes: Uint8Array; hashes: string[] }> {
  const sim = await Simulation.create({ scenario: getScenario(HEADER.scenario), params: HEADER.params, seed: HEADER.seed });
  const enc = new LogEncoder(HEADER);
  const parts = [enc.start()];
  const hashes = [sim.stateHash()];
  const script = new BotScript({ seed: 9, bots: 2, joinTicks: [0, 50] });
  try {
    for (let t = 0; t < 200; t++) {
      const rec = script.next();
      sim.step(rec);
      parts.push(enc.tick(opts.records ? opts.records(rec) : rec));
      hashes.push(sim.stateHash());
      if (sim.tick % HEADER.hashEveryTicks === 0) parts.push(enc.hash(sim.tick, opts.hashAt ? opts.hashAt(sim.tick, sim.stateHash()) : sim.stateHash()));
    }
    parts.push(enc.end(sim.tick, sim.stateHash()));
  } finally {
    sim.destroy();
  }
  return { bytes: Buffer.concat(parts), hashes };
}

describe('ReplayPlayer', () => {
  let player: ReplayPlayer | null = null;
  afterEach(() => {
    player?.destroy();
    player = null;
  });

  it('checks every recorded hash in one pass and seeks forward and back to the state of each tick', async () => {
    const { bytes, hashes } = await session();
    player = await ReplayPlayer.open(bytes, 'session.taoslog');
    expect(player.header.scenario).toBe('shape-rain');
    expect(player.totalTicks).toBe(200);
    expect(player.playersInLog().map((p) => p.playerId)).toEqual([1, 2]);
    const seen: number[] = [];
    const v = await player.verify((tick) => seen.push(tick));
    expect(v).toEqual({ hashesChecked: 11, firstMismatchTick: null, expected: null, actual: null, failure: null });
    expect(seen.at(-1)).toBe(200);
    for (const tick of [150, 151, 10, 0, 199, 200, 73]) {
      player.seek(tick);
      expect(player.tick).toBe(tick);
      expect(player.stateHash(), `state at tick ${tick}`).toBe(hashes[tick]);
    }
    // A small step forward reports that tick's events instead of a jump.
    player.seek(49);
    const step = player.seek(51);
    expect(step.jumped).toBe(false);
    expect(step.events.some((e) => e.type === 'playerJoined' && e.playerId === 2)).toBe(true);
    expect(player.seek(5).jumped).toBe(true);
    expect(player.frame().characters.map((c) => c.playerId)).toEqual([1]);
  });

  it('names the first tick whose recorded hash differs from this runtime', async () => {
    const { bytes } = await session({ hashAt: (tick, hash) => (tick >= 140 ? 'ffffffffffffffff' : hash) });
    player = await ReplayPlayer.open(bytes, 'bad.taoslog');
    const v = await player.verify();
    expect(v.firstMismatchTick).toBe(140);
    expect(v.expected).toBe('ffffffffffffffff');
    expect(v.actual).toMatch(/^[0-9a-f]{16}$/);
    expect(player.lastTick).toBe(200);
  });

  it('stops playback before a record the simulation cannot apply, saying why', async () => {
    const { bytes } = await session({ records: (r) => (r.tick === 120 ? { ...r, joins: [{ playerId: 1, name: 'twice' }] } : r) });
    player = await ReplayPlayer.open(bytes, 'odd.taoslog');
    const v = await player.verify();
    expect(v.failure).toMatch(/^tick record 120 cannot be applied: /);
    expect(player.lastTick).toBe(120);
    player.seek(500);
    expect(player.tick).toBe(120);
  });

  it('stops checking hashes with an error when the player is destroyed meanwhile', async () => {
    const { bytes } = await session();
    const p = await ReplayPlayer.open(bytes, 'session.taoslog');
    const checking = p.verify(() => p.destroy());
    await expect(checking).rejects.toThrow(/closed while its hashes were being checked/);
  });

  it('refuses bytes that are not an input log, and a log of an unknown scenario, with clear errors', async () => {
    await expect(ReplayPlayer.open(new Uint8Array([1, 2, 3]), 'junk.bin')).rejects.toThrow(/junk\.bin is not a taos-physics input log/);
    const enc = new LogEncoder({ ...HEADER, scenario: 'no-such-scene' });
    await expect(ReplayPlayer.open(enc.start(), 'other.taoslog')).rejects.toThrow(/other\.taoslog cannot be played by this build: unknown scenario "no-such-scene"/);
  });
});
