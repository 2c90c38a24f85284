// Tests of state dumps and divergence reports: identical sessions compare equal; a nudged body, a changed player or
// a missing body is named as the first difference.
import { describe, expect, it } from 'vitest';
import { firstDivergence, hashDump } from '../../../shared/sim/state-dump.ts';
import { pushBallScenario } from './helpers/game-scenarios.ts';
import { botRecords, IDLE, makeSim, record, runHashes } from './helpers/sim-helpers.ts';

describe('state-dump', () => {
  it('finds no difference between two identical sessions and hashes their dumps like stateHash', async () => {
    const records = botRecords(40);
    const a = await makeSim();
    const b = await makeSim();
    runHashes(a, records);
    runHashes(b, records);
    expect(a.firstDivergence(b)).toBeNull();
    expect(hashDump(a.dumpState())).toBe(a.stateHash());
    a.destroy();
    b.destroy();
  });

  it('streams, tick by tick, the hash of the full dump, with sensors, scenario state and game state in play', async () => {
    const arena = await makeSim();
    for (const r of botRecords(240, { bots: 3 })) {
      arena.step(r);
      expect(arena.stateHash(), `test-arena tick ${arena.tick}`).toBe(hashDump(arena.dumpState()));
    }
    expect(arena.dumpState().overlaps.length + arena.dumpState().scenarioState.length).toBeGreaterThan(0);
    arena.destroy();
    const ball = await makeSim(pushBallScenario);
    ball.step(record(0, { joins: [{ playerId: 1, name: 'p' }] }));
    for (let t = 1; t <= 40; t++) {
      ball.step(record(t, { commands: [{ playerId: 1, input: { ...IDLE, game: [t % 2, t % 3 === 0 ? 50 : 0] } }] }));
      expect(ball.stateHash(), `test-push-ball tick ${ball.tick}`).toBe(hashDump(ball.dumpState()));
    }
    expect(ball.gameState().pushTicks).toBeGreaterThan(0);
    ball.destroy();
  });

  it('names the first body whose state differs, and which field', async () => {
    const a = await makeSim();
    const dump = a.dumpState();
    const nudged = { ...dump, states: dump.states.slice() };
    nudged.states[4 * 13 + 8] += 1e-3; // fifth body's linear velocity y
    nudged.states[7 * 13 + 0] += 1e-3; // eighth body's position x
    const d = firstDivergence(dump, nudged);
    expect(d).toMatchObject({ part: 'body', bodyId: dump.ids[4] });
    expect(d!.detail).toContain('linearVelocity');
    a.destroy();
  });

  it('names a body that exists on one side only', async () => {
    const a = await makeSim();
    const dump = a.dumpState();
    const without = { ...dump, ids: dump.ids.slice(1), states: dump.states.slice(13), flags: dump.flags.slice(1) };
    expect(firstDivergence(dump, without)).toMatchObject({ part: 'ids', bodyId: dump.ids[0] });
    a.destroy();
  });

  it('names the player when only a player differs', async () => {
    const records = botRecords(30, { bots: 2, joinTicks: [0, 0] });
    const a = await makeSim();
    runHashes(a, records);
    const dump = a.dumpState();
    const other = { ...dump, players: dump.players.map((p, i) => (i === 1 ? { ...p, nextFireTick: p.nextFireTick + 1 } : p)) };
    expect(firstDivergence(dump, other)).toMatchObject({ part: 'players', playerId: dump.players[1].playerId });
    expect(hashDump(other)).not.toBe(hashDump(dump));
    a.destroy();
  });

  it('reports a different tick before anything else', async () => {
    const a = await makeSim();
    const dump = a.dumpState();
    expect(firstDivergence(dump, { ...dump, tick: 3 })?.part).toBe('tick');
    a.destroy();
  });
});
