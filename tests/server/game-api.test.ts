// The game API end to end on the in-process server: the SDK sends a scenario's named game input, the server checks
// it as untrusted input, and the room steps and records it; the scenario's game state reaches clients with snapshots,
// only when it changed, and the SDK reports it as typed state with change events; game messages are stamped with
// the room's next tick, recorded, and handled by the scenario.
import { afterEach, describe, expect, it } from 'vitest';
import { connect, type GameStateChange, type NetClient } from '../../sdk/index.ts';
import { ErrorCode } from '../../shared/protocol/index.ts';
import type { GameStateValues } from '../../shared/sim/game-state.ts';
import { NEUTRAL_INPUT } from '../../shared/sim/input.ts';
import type { Simulation } from '../../shared/sim/simulation.ts';
import { pickTeamScenario, pushBallScenario } from '../shared/sim/helpers/game-scenarios.ts';
import { MEMORY_URL, startHarness, type Harness } from './harness.ts';
import { stripScenario } from './test-scenarios.ts';

let h: Harness | null = null;
afterEach(async () => {
  await h?.close();
  h = null;
});

/** The default room's game state (the room runs a real Simulation). */
function roomState(harness: Harness): GameStateValues {
  return (harness.room().sim as Simulation).gameState();
}

async function sdkClient(harness: Harness, name: string): Promise<NetClient> {
  const c = connect(MEMORY_URL, { name, transport: harness.network().transport, clock: harness.clock, reconnect: false });
  await harness.settle(() => c.state === 'connected' || c.state === 'closed');
  expect(c.state).toBe('connected');
  return c;
}

describe('game input (server and SDK)', () => {
  it('tells the client the scenario\'s game input fields in the welcome, and runs the room in predict mode when asked', async () => {
    h = await startHarness({ scenarios: [pushBallScenario], netMode: 'predict' });
    const c = await sdkClient(h, 'ann');
    expect(c.welcome!.netMode).toBe('predict');
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

  it('keeps named values given before the welcome, and drops (and reports) the ones the scenario does not declare', async () => {
    h = await startHarness({ scenarios: [pushBallScenario] });
    const c = connect(MEMORY_URL, { name: 'early', transport: h.network().transport, clock: h.clock, reconnect: false });
    const problems: string[] = [];
    c.on('protocolError', (m) => problems.push(m));
    c.setInput({ ...NEUTRAL_INPUT, push: 30, kick: 1 });
    await h.settle(() => c.state === 'connected');
    expect(problems).toEqual(['setInput: the scenario declares no game input kick; dropped']);
    const room = h.room();
    const start = room.sim.tick;
    await h.settle(() => room.sim.tick > start + 10);
    const mine = h.history().records.flatMap((r) => r.commands).filter((cmd) => cmd.playerId === c.playerId);
    expect(mine.at(-1)!.input.game).toEqual([0, 30]);
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

describe('game state (server and SDK)', () => {
  it('names the state fields in the welcome and sends the whole state with the first snapshot', async () => {
    h = await startHarness({ scenarios: [pushBallScenario] });
    const t = await h.join('raw');
    expect(t.welcome!.scenario.game?.state).toEqual([
      { name: 'phase', kind: 'string', maxLength: 8 },
      { name: 'pushTicks', kind: 'number', maxLength: 0 },
    ]);
    await h.settle(() => t.ofType('snapshot').length >= 1);
    expect(t.ofType('snapshot')[0].state).toEqual(['idle', 0]);
  });

  it('sends state again only with snapshots after it changed', async () => {
    h = await startHarness({ scenarios: [pushBallScenario] });
    const t = await h.join('raw');
    const room = h.room();
    await h.settle(() => t.ofType('snapshot').length >= 10);
    expect(t.ofType('snapshot').filter((m) => m.state !== undefined)).toHaveLength(1);
    // Four ticks of pushing, then idle: snapshots (30 Hz) sample the state at their tick.
    const from = room.sim.tick + 2;
    t.input(from, [{ ...NEUTRAL_INPUT, game: [0, 50] }, { ...NEUTRAL_INPUT, game: [0, 50] }, { ...NEUTRAL_INPUT, game: [0, 50] }, { ...NEUTRAL_INPUT, game: [0, 50] }, NEUTRAL_INPUT]);
    await h.settle(() => room.sim.tick > from + 20);
    const states = t.ofType('snapshot').flatMap((m) => (m.state === undefined ? [] : [m.state]));
    expect(states[0]).toEqual(['idle', 0]);
    expect(states.at(-1)).toEqual(['idle', 4]);
    expect(states.length).toBeGreaterThanOrEqual(3);
    expect(states.slice(1, -1).every((v) => v[0] === 'pushing')).toBe(true);
    for (let i = 1; i < states.length; i++) expect(states[i]).not.toEqual(states[i - 1]);
  });

  it('exposes the state in the SDK and reports each change with the names that changed', async () => {
    h = await startHarness({ scenarios: [pushBallScenario] });
    const c = await sdkClient(h, 'ann');
    const changes: GameStateChange[] = [];
    c.on('gameState', (change) => changes.push(change));
    await h.settle(() => changes.length >= 1);
    expect(c.gameState<{ phase: string; pushTicks: number }>()).toEqual({ phase: 'idle', pushTicks: 0 });
    c.setInput({ ...NEUTRAL_INPUT, push: 10 });
    await h.settle(() => (c.gameState<{ pushTicks: number }>().pushTicks ?? 0) >= 3);
    expect(changes[0].changed).toEqual(['phase', 'pushTicks']);
    expect(changes[1].changed).toContain('phase');
    expect(changes[1].state.phase).toBe('pushing');
    expect(changes.slice(2).every((ch) => ch.changed.join() === 'pushTicks')).toBe(true);
    c.close();
  });
});

describe('game messages (server and SDK)', () => {
  it('stamps an SDK message into the next tick\'s record, where the scenario handles it', async () => {
    h = await startHarness({ scenarios: [pickTeamScenario] });
    const c = await sdkClient(h, 'ann');
    expect(c.welcome!.scenario.game?.messages?.map((k) => k.name)).toEqual(['pickTeam', 'ready']);
    c.sendMessage('pickTeam', { team: 1 });
    await h.settle(() => c.gameState<{ lastPick: number }>().lastPick === c.playerId! * 10 + 1);
    const stamped = h.history().records.filter((r) => r.messages !== undefined);
    expect(stamped.map((r) => r.messages)).toEqual([[{ playerId: c.playerId, name: 'pickTeam', payload: [1] }]]);
    expect(roomState(h)).toMatchObject({ lastPick: c.playerId! * 10 + 1 });
    c.close();
  });

  it('throws in the SDK for an undeclared message, payload field or value', async () => {
    h = await startHarness({ scenarios: [pickTeamScenario] });
    const c = await sdkClient(h, 'ann');
    expect(() => c.sendMessage('jump')).toThrow(/unknown message "jump" \(declared: pickTeam, ready\)/);
    expect(() => c.sendMessage('pickTeam', { side: 1 })).toThrow(/no payload field "side" \(declared: team\)/);
    expect(() => c.sendMessage('pickTeam', { team: 3 })).toThrow(/team must be in \[0, 1\], got 3/);
    c.close();
    expect(() => c.sendMessage('ready')).toThrow(/not connected/);
  });

  it('answers a hostile message with bad-message and records nothing for it', async () => {
    h = await startHarness({ scenarios: [pickTeamScenario] });
    const t = await h.join('raw');
    t.send({ type: 'game', name: 'pickTeam', payload: [7] });
    t.send({ type: 'game', name: 'nope', payload: [] });
    t.send({ type: 'game', name: 'pickTeam', payload: [1, 1] });
    await h.settle(() => t.ofType('error').length >= 3);
    expect(t.ofType('error').map((e) => [e.code, e.message])).toEqual([
      [ErrorCode.BadMessage, 'game: message pickTeam: team must be in [0, 1], got 7'],
      [ErrorCode.BadMessage, 'game: unknown message "nope" (declared: pickTeam, ready)'],
      [ErrorCode.BadMessage, 'game: message pickTeam needs 1 payload value(s) (team), got 2'],
    ]);
    h.ticks(5);
    expect(h.history().records.some((r) => r.messages !== undefined)).toBe(false);
    expect(t.closed).toBeNull();
  });

  it('applies a message on the tick it names, on the next tick when that one has passed, and no later than the input lead limit', async () => {
    h = await startHarness({ scenarios: [pickTeamScenario] });
    const t = await h.join('raw');
    const next = h.room().sim.tick;
    t.send({ type: 'game', name: 'pickTeam', payload: [1], tick: next + 20 });
    t.send({ type: 'game', name: 'ready', payload: [], tick: Math.max(0, next - 5) });
    t.send({ type: 'game', name: 'ready', payload: [], tick: next + 100_000 });
    await h.settle(() => h!.history().records.filter((r) => r.messages !== undefined).length >= 3, 5000);
    const stamped = h.history().records.filter((r) => r.messages !== undefined).map((r) => [r.tick, r.messages!.map((m) => m.name)]);
    expect(stamped[0]).toEqual([expect.any(Number), ['ready']]);
    expect(stamped[0][0]).toBeLessThan(next + 20);
    expect(stamped[1]).toEqual([next + 20, ['pickTeam']]);
    // The room's default input lead limit is 120 ticks past the tick it arrived before.
    expect(stamped[2][1]).toEqual(['ready']);
    expect(stamped[2][0]).toBeLessThanOrEqual(next + 130);
    expect(stamped[2][0]).toBeGreaterThan(next + 100);
    expect(t.ofType('error')).toEqual([]);
  });

  it('refuses more than eight messages from one player in one tick', async () => {
    h = await startHarness({ scenarios: [pickTeamScenario] });
    const t = await h.join('raw');
    for (let i = 0; i < 9; i++) t.send({ type: 'game', name: 'ready', payload: [] });
    await h.settle(() => t.ofType('error').length >= 1 || roomState(h!).readies !== 0);
    await h.settle(() => roomState(h!).readies !== 0);
    expect(t.ofType('error').map((e) => e.message)).toEqual(['game: at most 8 game messages per tick']);
    expect(roomState(h).readies).toBe(8);
  });
});
