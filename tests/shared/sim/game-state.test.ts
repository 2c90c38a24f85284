// Tests of replicated game state in the simulation: declarations are checked, the scenario publishes and reads
// values, bad values fail the tick with a clear message, and the state is hashed, checkpointed and replayed.
import { describe, expect, it } from 'vitest';
import { GameStateStore, resolveGameStateFields } from '../../../shared/sim/game-state.ts';
import type { ScenarioDefinition } from '../../../shared/sim/scenario.ts';
import { Simulation } from '../../../shared/sim/simulation.ts';
import type { TickInputRecord } from '../../../shared/sim/types.ts';
import { pushBallScenario } from './helpers/game-scenarios.ts';
import { IDLE, makeSim, record, runHashes } from './helpers/sim-helpers.ts';

function pushSession(n: number, push: number): TickInputRecord[] {
  const out = [record(0, { joins: [{ playerId: 1, name: 'p' }] })];
  for (let t = 1; t <= n; t++) out.push(record(t, { commands: [{ playerId: 1, input: { ...IDLE, game: [0, push] } }] }));
  return out;
}

describe('game state (simulation)', () => {
  it('starts from the declared initial values', async () => {
    const sim = await makeSim(pushBallScenario);
    expect(sim.gameState()).toEqual({ phase: 'idle', pushTicks: 0 });
    expect(sim.gameStateFields.map((f) => [f.name, f.kind, f.maxLength])).toEqual([
      ['phase', 'string', 8],
      ['pushTicks', 'number', 0],
    ]);
    sim.destroy();
  });

  it('holds what the scenario published on each tick', async () => {
    const sim = await makeSim(pushBallScenario);
    runHashes(sim, pushSession(12, 30));
    expect(sim.gameState()).toEqual({ phase: 'pushing', pushTicks: 12 });
    sim.step(record(13, { commands: [{ playerId: 1, input: IDLE }] }));
    expect(sim.gameState()).toEqual({ phase: 'idle', pushTicks: 12 });
    sim.destroy();
  });

  it('changes its version only when a value changes', () => {
    const store = new GameStateStore(resolveGameStateFields({ score: { kind: 'number' } }, 't'));
    store.set('score', 0);
    expect(store.version).toBe(0);
    store.set('score', 2);
    store.set('score', 2);
    expect(store.version).toBe(1);
    store.set('score', -0);
    expect(Object.is(store.get('score'), 0)).toBe(true);
  });

  it('fails the tick with a clear message when the scenario sets an undeclared field or a value of the wrong kind', async () => {
    const setting = (name: string, value: unknown): ScenarioDefinition => ({
      ...pushBallScenario,
      build: () => ({ spawnPoint: () => ({ x: 0, y: 1, z: 0 }), onTick: (c) => c.setState(name, value as number) }),
    });
    const cases: Array<[string, unknown, RegExp]> = [
      ['score', 1, /unknown state field "score" \(declared: phase, pushTicks\)/],
      ['pushTicks', 'x', /pushTicks must be a finite number, got "x"/],
      ['pushTicks', Number.NaN, /pushTicks must be a finite number, got NaN/],
      ['phase', 'far too long', /phase must be at most 8 characters, got 12/],
    ];
    for (const [name, value, error] of cases) {
      const sim = await makeSim(setting(name, value));
      expect(() => sim.step(record(0))).toThrow(error);
      sim.destroy();
    }
  });

  it('refuses bad declarations when the simulation is created', async () => {
    const bad = (state: unknown): ScenarioDefinition => ({ ...pushBallScenario, state: state as ScenarioDefinition['state'] });
    await expect(Simulation.create({ scenario: bad({ s: { kind: 'string', maxLength: 65 } }) })).rejects.toThrow(/maxLength must be an integer in \[1, 64\]/);
    await expect(Simulation.create({ scenario: bad({ s: { kind: 'boolean' } }) })).rejects.toThrow(/kind must be 'number' or 'string'/);
    await expect(Simulation.create({ scenario: bad({ s: { kind: 'number', initial: 'x' } }) })).rejects.toThrow(/initial value: s must be a finite number/);
    const many = Object.fromEntries(Array.from({ length: 33 }, (_, i) => [`f${i}`, { kind: 'number' }]));
    await expect(Simulation.create({ scenario: bad(many) })).rejects.toThrow(/at most 32 game state fields/);
  });

  it('hashes the game state: two runs that differ only in it hash differently', async () => {
    const counting = (start: number): ScenarioDefinition => ({ ...pushBallScenario, state: { n: { kind: 'number', initial: start } }, build: () => ({ spawnPoint: () => ({ x: 0, y: 1, z: 0 }) }) });
    const a = await makeSim(counting(1));
    const b = await makeSim(counting(2));
    expect(a.stateHash()).not.toBe(b.stateHash());
    expect(a.firstDivergence(b)).toMatchObject({ part: 'scenario', detail: 'game state differs' });
    a.destroy();
    b.destroy();
  });

  it('restores the game state from fast and byte checkpoints', async () => {
    const sim = await makeSim(pushBallScenario);
    runHashes(sim, pushSession(5, 20));
    const fast = sim.saveCheckpoint();
    const bytes = sim.saveCheckpointBytes();
    sim.step(record(6, { commands: [{ playerId: 1, input: { ...IDLE, game: [0, 20] } }] }));
    expect(sim.gameState().pushTicks).toBe(6);
    sim.restoreCheckpoint(fast);
    expect(sim.gameState()).toEqual({ phase: 'pushing', pushTicks: 5 });
    fast.dispose();
    const other = await makeSim(pushBallScenario);
    other.restoreCheckpointBytes(bytes);
    expect(other.gameState()).toEqual({ phase: 'pushing', pushTicks: 5 });
    expect(other.stateHash()).toBe(sim.stateHash());
    sim.destroy();
    other.destroy();
  });
});
