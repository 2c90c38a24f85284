// Tests of game-defined input in the simulation: declared fields are checked when the simulation is created, the
// values steer the scenario, enter the state hash, survive checkpoints and replay from the input log.
import { describe, expect, it } from 'vitest';
import { decodeTick, encodeTick } from '../../../server/log/record-codec.ts';
import type { ScenarioDefinition } from '../../../shared/sim/scenario.ts';
import { Simulation } from '../../../shared/sim/simulation.ts';
import type { TickInputRecord } from '../../../shared/sim/types.ts';
import { pushBallScenario, PUSH_BALL_ID } from './helpers/game-scenarios.ts';
import { IDLE, makeSim, record, runHashes } from './helpers/sim-helpers.ts';
import { testArena } from './helpers/test-scenarios.ts';

/** Player 1 joins, then pushes with `push` on ticks 1..n. */
function pushSession(n: number, push: number, lift = 0): TickInputRecord[] {
  const out = [record(0, { joins: [{ playerId: 1, name: 'p' }] })];
  for (let t = 1; t <= n; t++) out.push(record(t, { commands: [{ playerId: 1, input: { ...IDLE, game: [lift, push] } }] }));
  return out;
}

describe('game input (simulation)', () => {
  it('orders the declared fields by name', async () => {
    const sim = await makeSim(pushBallScenario);
    expect(sim.gameInputFields).toEqual([
      { name: 'lift', min: 0, max: 1 },
      { name: 'push', min: -100, max: 100 },
    ]);
    sim.destroy();
  });

  it('moves the ball with the pushing player\'s axis value', async () => {
    const sim = await makeSim(pushBallScenario);
    runHashes(sim, pushSession(30, 100));
    expect(sim.world.getBody(PUSH_BALL_ID)!.position().x).toBeGreaterThan(1.5);
    sim.destroy();
  });

  it('hashes game input: the same session with another push value hashes differently from its first push', async () => {
    const a = runHashes(await makeSim(pushBallScenario), pushSession(3, 40));
    const b = runHashes(await makeSim(pushBallScenario), pushSession(3, 41));
    expect(a[0]).toBe(b[0]);
    expect(a[1]).not.toBe(b[1]);
  });

  it('fills a command without game values with zeros', async () => {
    const a = await makeSim(pushBallScenario);
    const b = await makeSim(pushBallScenario);
    const join = record(0, { joins: [{ playerId: 1, name: 'p' }] });
    const ha = runHashes(a, [join, record(1, { commands: [{ playerId: 1, input: IDLE }] })]);
    const hb = runHashes(b, [join, record(1, { commands: [{ playerId: 1, input: { ...IDLE, game: [0, 0] } }] })]);
    expect(ha).toEqual(hb);
    a.destroy();
    b.destroy();
  });

  it('refuses out-of-range, wrong-length or undeclared game values and changes nothing', async () => {
    const sim = await makeSim(pushBallScenario);
    sim.step(record(0, { joins: [{ playerId: 1, name: 'p' }] }));
    const before = sim.stateHash();
    expect(() => sim.step(record(1, { commands: [{ playerId: 1, input: { ...IDLE, game: [0, 101] } }] }))).toThrow(/outside the declared ranges/);
    expect(() => sim.step(record(1, { commands: [{ playerId: 1, input: { ...IDLE, game: [1] } }] }))).toThrow(/must have 2 values \(lift, push\)/);
    expect(() => sim.step(record(1, { commands: [{ playerId: 1, input: { ...IDLE, game: [0, Number.NaN] } }] }))).toThrow(/game\[1\] must be finite/);
    expect(sim.stateHash()).toBe(before);
    sim.destroy();
    const plain = await makeSim(testArena);
    plain.step(record(0, { joins: [{ playerId: 1, name: 'p' }] }));
    expect(() => plain.step(record(1, { commands: [{ playerId: 1, input: { ...IDLE, game: [1] } }] }))).toThrow(/declares no game input fields/);
    plain.destroy();
  });

  it('refuses bad declarations when the simulation is created', async () => {
    const bad = (input: unknown): ScenarioDefinition => ({ ...pushBallScenario, input: input as ScenarioDefinition['input'] });
    await expect(Simulation.create({ scenario: bad({ moveX: { kind: 'button' } }) })).rejects.toThrow(/taken by the built-in command/);
    await expect(Simulation.create({ scenario: bad({ 'a b': { kind: 'button' } }) })).rejects.toThrow(/identifiers/);
    await expect(Simulation.create({ scenario: bad({ x: { kind: 'axis', min: 3, max: 3 } }) })).rejects.toThrow(/integer min < max/);
    await expect(Simulation.create({ scenario: bad({ x: { kind: 'trigger' } }) })).rejects.toThrow(/kind must be 'button' or 'axis'/);
    const many = Object.fromEntries(Array.from({ length: 17 }, (_, i) => [`f${i}`, { kind: 'button' }]));
    await expect(Simulation.create({ scenario: bad(many) })).rejects.toThrow(/at most 16/);
  });

  it('replays from log-encoded records with the same hash every tick', async () => {
    const session = pushSession(40, -73, 1);
    const live = runHashes(await makeSim(pushBallScenario), session);
    const decoded = session.map((r) => decodeTick(encodeTick(r)));
    expect(decoded[5].commands[0].input.game).toEqual([1, -73]);
    expect(runHashes(await makeSim(pushBallScenario), decoded)).toEqual(live);
  });

  it('restores game input from a byte checkpoint: later ticks hash as in the original run', async () => {
    const session = pushSession(20, 55, 1);
    // Player 1 keeps its last command through ticks with no command, so the restored input must be the saved one.
    const idleAfter = Array.from({ length: 10 }, (_, i) => record(21 + i));
    const a = await makeSim(pushBallScenario);
    runHashes(a, session);
    const bytes = a.saveCheckpointBytes();
    const tail = runHashes(a, idleAfter);
    const b = await makeSim(pushBallScenario);
    b.restoreCheckpointBytes(bytes);
    expect(runHashes(b, idleAfter)).toEqual(tail);
    a.destroy();
    b.destroy();
  });
});
