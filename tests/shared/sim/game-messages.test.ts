// Tests of game messages in the simulation: declared kinds are checked when the simulation is created, messages in a
// tick's record reach the scenario's onMessage in record order, bad ones are refused before anything applies, and a
// session with messages replays from the input log with the same hashes.
import { describe, expect, it } from 'vitest';
import { decodeTick, encodeTick } from '../../../server/log/record-codec.ts';
import type { GameMessage } from '../../../shared/sim/game-messages.ts';
import type { ScenarioDefinition } from '../../../shared/sim/scenario.ts';
import { Simulation } from '../../../shared/sim/simulation.ts';
import type { TickInputRecord } from '../../../shared/sim/types.ts';
import { pickTeamScenario } from './helpers/game-scenarios.ts';
import { makeSim, record, runHashes } from './helpers/sim-helpers.ts';

const joins = record(0, { joins: [{ playerId: 1, name: 'a' }, { playerId: 2, name: 'b' }] });
const withMessages = (tick: number, messages: GameMessage[]): TickInputRecord => ({ ...record(tick), messages });

describe('game messages (simulation)', () => {
  it('resolves the declared kinds with their payload fields in name order', async () => {
    const sim = await makeSim(pickTeamScenario);
    expect(sim.gameMessageKinds).toEqual([
      { name: 'pickTeam', fields: [{ name: 'team', min: 0, max: 1 }] },
      { name: 'ready', fields: [] },
    ]);
    sim.destroy();
  });

  it('hands each message to onMessage in record order on its tick', async () => {
    const sim = await makeSim(pickTeamScenario);
    sim.step(joins);
    sim.step(withMessages(1, [{ playerId: 1, name: 'ready', payload: [] }, { playerId: 2, name: 'pickTeam', payload: [1] }, { playerId: 2, name: 'ready', payload: [] }]));
    expect(sim.gameState()).toMatchObject({ lastPick: 21, readies: 2 });
    sim.step(withMessages(2, [{ playerId: 1, name: 'pickTeam', payload: [0] }]));
    expect(sim.gameState()).toMatchObject({ lastPick: 10, readies: 2 });
    sim.destroy();
  });

  it('refuses undeclared, malformed, out-of-range and misplaced messages and changes nothing', async () => {
    const sim = await makeSim(pickTeamScenario);
    sim.step(joins);
    const before = sim.stateHash();
    const cases: Array<[GameMessage[], RegExp]> = [
      [[{ playerId: 1, name: 'jump', payload: [] }], /unknown message "jump" \(declared: pickTeam, ready\)/],
      [[{ playerId: 1, name: 'pickTeam', payload: [] }], /pickTeam needs 1 payload value\(s\) \(team\), got 0/],
      [[{ playerId: 1, name: 'pickTeam', payload: [2] }], /team must be in \[0, 1\], got 2/],
      [[{ playerId: 1, name: 'pickTeam', payload: [0.5] }], /payload\[0\] must be an integer/],
      [[{ playerId: 9, name: 'ready', payload: [] }], /message from player 9, who is not in the game/],
      [[{ playerId: 2, name: 'ready', payload: [] }, { playerId: 1, name: 'ready', payload: [] }], /sorted by player id/],
      [Array.from({ length: 9 }, () => ({ playerId: 1, name: 'ready', payload: [] })), /more than 8 messages/],
    ];
    for (const [messages, error] of cases) {
      expect(() => sim.step(withMessages(1, messages))).toThrow(error);
      expect(sim.stateHash()).toBe(before);
    }
    sim.destroy();
  });

  it('refuses bad declarations when the simulation is created', async () => {
    const bad = (messages: unknown): ScenarioDefinition => ({ ...pickTeamScenario, messages: messages as ScenarioDefinition['messages'] });
    await expect(Simulation.create({ scenario: bad({ 'pick team': {} }) })).rejects.toThrow(/identifiers/);
    await expect(Simulation.create({ scenario: bad({ pick: { payload: { t: { min: 2, max: 1 } } } }) })).rejects.toThrow(/integer min ≤ max/);
    const wide = { pick: { payload: Object.fromEntries(Array.from({ length: 9 }, (_, i) => [`f${i}`, { min: 0, max: 1 }])) } };
    await expect(Simulation.create({ scenario: bad(wide) })).rejects.toThrow(/at most 8 payload fields/);
  });

  it('replays a session with messages from log-encoded records with the same hash every tick', async () => {
    const session = [joins, withMessages(1, [{ playerId: 1, name: 'pickTeam', payload: [1] }]), record(2), withMessages(3, [{ playerId: 2, name: 'ready', payload: [] }])];
    const live = runHashes(await makeSim(pickTeamScenario), session);
    const decoded = session.map((r) => decodeTick(encodeTick(r)));
    expect(decoded[1].messages).toEqual([{ playerId: 1, name: 'pickTeam', payload: [1] }]);
    expect(decoded[2]).toEqual(record(2));
    expect(runHashes(await makeSim(pickTeamScenario), decoded)).toEqual(live);
  });
});
