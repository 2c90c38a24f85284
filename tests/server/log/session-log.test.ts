// Tests for SessionLog: a simulation stepped through it leaves a log of its inputs, hashes and checkpoints, and a
// record the simulation would reject is refused before anything is logged.
import '../../../server/physics-node.ts';
import { mkdtemp, readFile, rm } from 'node:fs/promises';
import { tmpdir } from 'node:os';
import { join } from 'node:path';
import { afterAll, beforeAll, describe, expect, it } from 'vitest';
import { readLogBytes } from '../../../server/log/log-bytes.ts';
import { SessionLog } from '../../../server/log/session-log.ts';
import { getScenario } from '../../../scenarios/index.ts';
import { BotScript } from '../../../shared/sim/bots.ts';
import { Simulation } from '../../../shared/sim/simulation.ts';
import { emptyTickInput } from '../../../shared/sim/types.ts';

let dir = '';
beforeAll(async () => {
  dir = await mkdtemp(join(tmpdir(), 'taos-session-log-'));
});
afterAll(async () => {
  await rm(dir, { recursive: true, force: true });
});

describe('session-log', () => {
  it('logs each record before applying it, with the hashes and checkpoints due, and restores from a checkpoint', async () => {
    const sim = await Simulation.create({ scenario: getScenario('character-course'), seed: 5 });
    const path = join(dir, 's.taoslog');
    const session = await SessionLog.create(path, sim, { hashEveryTicks: 2, checkpointEveryTicks: 10 });
    const bots = new BotScript({ seed: 5, bots: 2 });
    const hashes = new Map<number, string>([[0, sim.stateHash()]]);
    for (let t = 0; t < 20; t++) {
      session.step(bots.next());
      hashes.set(sim.tick, sim.stateHash());
    }
    await session.close();
    const { header, entries, outcome } = readLogBytes(await readFile(path));
    expect(outcome.status).toBe('complete');
    expect(header).toMatchObject({ scenario: 'character-course', seed: 5, hashEveryTicks: 2, checkpointEveryTicks: 10 });
    expect(header.params).toEqual({ ...sim.params });
    for (const e of entries) if (e.type === 'hash' || e.type === 'end') expect(e.hash).toBe(hashes.get(e.tick));
    expect(entries.filter((e) => e.type === 'hash').map((e) => (e.type === 'hash' ? e.tick : -1))).toEqual([0, 2, 4, 6, 8, 10, 12, 14, 16, 18, 20]);
    const cp = entries.find((e) => e.type === 'checkpoint' && e.tick === 10);
    if (cp?.type !== 'checkpoint') throw new Error('no checkpoint at tick 10');
    const again = await Simulation.create({ scenario: getScenario('character-course'), seed: 5 });
    again.restoreCheckpointBytes(cp.bytes);
    expect(again.tick).toBe(10);
    expect(again.stateHash()).toBe(hashes.get(10));
    again.destroy();
    sim.destroy();
  });

  it('refuses a record the simulation would reject, logging nothing, and carries on', async () => {
    const sim = await Simulation.create({ scenario: getScenario('character-course') });
    const path = join(dir, 'reject.taoslog');
    const session = await SessionLog.create(path, sim);
    session.step({ ...emptyTickInput(0), joins: [{ playerId: 4, name: 'a' }] });
    expect(() => session.step({ ...emptyTickInput(1), leaves: [9] })).toThrow(/player 9 cannot leave, it is not in the game/);
    expect(() => session.step(emptyTickInput(5))).toThrow(/record for tick 5 given, but the simulation is at tick 1/);
    session.step({ ...emptyTickInput(1), leaves: [4] });
    await session.close();
    const { entries, outcome } = readLogBytes(await readFile(path));
    expect(outcome.status).toBe('complete');
    expect(entries.filter((e) => e.type === 'tick').map((e) => (e.type === 'tick' ? e.record : null))).toEqual([
      { ...emptyTickInput(0), joins: [{ playerId: 4, name: 'a' }] },
      { ...emptyTickInput(1), leaves: [4] },
    ]);
    await expect(SessionLog.create(join(dir, 'late.taoslog'), sim)).rejects.toThrow(/must be at tick 0 \(it is at 2\)/);
    sim.destroy();
  });
});
