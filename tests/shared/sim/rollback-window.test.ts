// GGRS-style sync test over every built-in scenario: each tick rolls back N ticks through the window's fast
// checkpoints and re-simulates them with the same inputs; every re-simulated hash must equal a plain run's. Also for a
// scenario on the game API, with game input, game messages and game state rolled back.
import { describe, expect, it } from 'vitest';
import { listScenarios } from '../../../scenarios/index.ts';
import { Prng } from '../../../shared/sim/prng.ts';
import { RollbackWindow } from '../../../shared/sim/rollback-window.ts';
import { Simulation } from '../../../shared/sim/simulation.ts';
import type { TickInputRecord } from '../../../shared/sim/types.ts';
import { botRecords, hashesOf } from '../../helpers/scenario-sim.ts';
import { pickTeamScenario } from './helpers/game-scenarios.ts';

const ROLLBACK_TICKS = 8;
const RUN_TICKS = 75;
const BOTS = 3;

describe('rollback-window', () => {
  for (const def of listScenarios()) {
    it(`re-simulates ${ROLLBACK_TICKS} ticks back every tick with the plain run's hashes (${def.name})`, async () => {
      const records = botRecords(11, BOTS, RUN_TICKS);
      const plain = await Simulation.create({ scenario: def, seed: 7 });
      const synced = await Simulation.create({ scenario: def, seed: 7 });
      const window = new RollbackWindow(synced, ROLLBACK_TICKS + 1);
      try {
        const expected = hashesOf(plain, records);
        expect(new Set(expected).size).toBeGreaterThan(RUN_TICKS / 2);
        let rollbacks = 0;
        for (const r of records) {
          window.step(r);
          expect(synced.stateHash(), `tick ${r.tick}`).toBe(expected[r.tick]);
          const from = r.tick + 1 - ROLLBACK_TICKS;
          if (from < 0) continue;
          window.restore(from);
          expect(synced.tick).toBe(from);
          for (let t = from; t <= r.tick; t++) {
            window.step(records[t]);
            expect(synced.stateHash(), `tick ${t} re-simulated after tick ${r.tick}`).toBe(expected[t]);
          }
          rollbacks++;
        }
        expect(rollbacks).toBe(RUN_TICKS - ROLLBACK_TICKS + 1);
      } finally {
        window.dispose();
        plain.destroy();
        synced.destroy();
      }
    });
  }

  it('re-simulates a game-API scenario with game input and messages, its game state included', async () => {
    // Bots pushing the ball with game input now and then, and a pickTeam or ready message every few ticks.
    const rng = new Prng(5);
    const present = new Set<number>();
    const records: TickInputRecord[] = botRecords(11, BOTS, 150).map((r) => {
      for (const j of r.joins) present.add(j.playerId);
      for (const id of r.leaves) present.delete(id);
      const commands = r.commands.map((c) => ({ ...c, input: { ...c.input, game: [rng.next() < 0.2 ? 1 : 0, rng.next() < 0.5 ? 0 : rng.int(-100, 100)] } }));
      const sender = [...present].sort((a, b) => a - b)[rng.int(0, present.size - 1)];
      const message = rng.next() < 0.5 ? { playerId: sender, name: 'pickTeam', payload: [rng.int(0, 1)] } : { playerId: sender, name: 'ready', payload: [] };
      return sender !== undefined && r.tick % 7 === 3 ? { ...r, commands, messages: [message] } : { ...r, commands };
    });
    const plain = await Simulation.create({ scenario: pickTeamScenario, seed: 7 });
    const synced = await Simulation.create({ scenario: pickTeamScenario, seed: 7 });
    const window = new RollbackWindow(synced, ROLLBACK_TICKS + 1);
    try {
      const states = records.map((r) => (plain.step(r), { hash: plain.stateHash(), state: plain.gameState() }));
      expect(new Set(states.map((s) => s.hash)).size).toBeGreaterThan(100);
      expect(new Set(states.map((s) => JSON.stringify(s.state))).size).toBeGreaterThan(30);
      for (const r of records) {
        window.step(r);
        const from = Math.max(0, r.tick + 1 - ROLLBACK_TICKS);
        window.restore(from);
        for (let t = from; t <= r.tick; t++) window.step(records[t]);
        expect(synced.stateHash(), `tick ${r.tick}`).toBe(states[r.tick].hash);
        expect(synced.gameState(), `tick ${r.tick}`).toEqual(states[r.tick].state);
      }
    } finally {
      window.dispose();
      plain.destroy();
      synced.destroy();
    }
  });

  it('keeps only its capacity and names the ticks it holds when asked for an older one', async () => {
    const def = listScenarios().find((s) => s.name === 'character-course')!;
    const sim = await Simulation.create({ scenario: def });
    const window = new RollbackWindow(sim, 4);
    try {
      for (const r of botRecords(2, 1, 10)) window.step(r);
      expect(window.size).toBe(4);
      expect(window.oldestTick).toBe(6);
      expect(window.canRestore(5)).toBe(false);
      expect(() => window.restore(5)).toThrow(/no checkpoint for tick 5 \(holding ticks 6\.\.9\)/);
      window.forgetBefore(8);
      expect(window.oldestTick).toBe(8);
      window.restore(8);
      expect(sim.tick).toBe(8);
      expect(window.size).toBe(1);
    } finally {
      window.dispose();
      sim.destroy();
    }
  });
});
