// The game API end to end on the in-process server: the SDK sends a scenario's named game input, the server checks
// it as untrusted input, and the room steps and records it.
import { afterEach, describe, expect, it } from 'vitest';
import { connect, type NetClient } from '../../sdk/index.ts';
import { ErrorCode } from '../../shared/protocol/index.ts';
import { NEUTRAL_INPUT } from '../../shared/sim/input.ts';
import { pushBallScenario } from '../shared/sim/helpers/game-scenarios.ts';
import { MEMORY_URL, startHarness, type Harness } from './harness.ts';
import { stripScenario } from './test-scenarios.ts';

let h: Harness | null = null;
afterEach(async () => {
  await h?.close();
  h = null;
});

async function sdkClient(harness: Harness, name: string): Promise<NetClient> {
  const c = connect(MEMORY_URL, { name, transport: harness.network().transport, clock: harness.clock, reconnect: false });
  await harness.settle(() => c.state === 'connected' || c.state === 'closed');
  expect(c.state).toBe('connected');
  return c;
}

describe('game input (server and SDK)', () => {
  it('tells the client the scenario\'s game input fields in the welcome', async () => {
    h = await startHarness({ scenarios: [pushBallScenario] });
    const c = await sdkClient(h, 'ann');
    expect(c.welcome!.scenario.game?.input).toEqual([
      { name: 'lift', min: 0, max: 1 },
      { name: 'push', min: -100, max: 100 },
    ]);
    c.close();
  });

  it('steps and records the named values the SDK sends, in field order', async () => {
    h = await startHarness({ scenarios: [pushBallScenario] });
    const c = await sdkClient(h, 'ann');
    c.setInput({ ...NEUTRAL_INPUT, push: -60, lift: 1 });
    const room = h.room();
    const start = room.sim.tick;
    await h.settle(() => room.sim.tick > start + 20);
    const mine = h.history().records.flatMap((r) => r.commands).filter((cmd) => cmd.playerId === c.playerId);
    expect(mine.at(-1)!.input.game).toEqual([1, -60]);
    c.close();
  });

  it('refuses a field the scenario does not declare once the welcome named the fields', async () => {
    h = await startHarness({ scenarios: [pushBallScenario] });
    const c = await sdkClient(h, 'ann');
    expect(() => c.setInput({ ...NEUTRAL_INPUT, kick: 1 })).toThrow(/unknown game input field "kick" \(declared: lift, push\)/);
    expect(() => c.setInput({ ...NEUTRAL_INPUT, push: Number.NaN })).toThrow(/push must be a finite number/);
    c.close();
  });

  it('clamps values into the declared range and refuses a wrong count with bad-input, keeping the connection', async () => {
    h = await startHarness({ scenarios: [pushBallScenario] });
    const t = await h.join('raw');
    const room = h.room();
    const tick = room.sim.tick + 2;
    t.input(tick, [{ ...NEUTRAL_INPUT, game: [7, 5000] }]);
    t.input(tick + 1, [{ ...NEUTRAL_INPUT, game: [1] }]);
    await h.settle(() => room.sim.tick > tick + 2);
    const applied = h.history().records.find((r) => r.tick === tick)!.commands.find((cmd) => cmd.playerId === t.playerId)!;
    expect(applied.input.game).toEqual([1, 100]);
    expect(t.ofType('error').map((e) => [e.code, e.message])).toEqual([[ErrorCode.BadInput, 'input.commands[0] (tick ' + (tick + 1) + '): game input must have 2 values (lift, push), got 1']]);
    expect(t.closed).toBeNull();
  });

  it('refuses game values in a scenario that declares none', async () => {
    h = await startHarness({ scenarios: [stripScenario] });
    const t = await h.join('raw');
    t.input(h.room().sim.tick + 2, [{ ...NEUTRAL_INPUT, game: [1] }]);
    await h.settle(() => t.ofType('error').length > 0);
    expect(t.ofType('error')[0].message).toMatch(/declares no game input fields/);
  });
});
