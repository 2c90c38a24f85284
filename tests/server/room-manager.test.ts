// Tests for server/room-manager.ts and server/room-factory.ts through the harness: rooms on demand (by scenario name
// or API), joining by id, the rooms limit, closing empty rooms after the grace period, the heap guard and per-room Jolt modules.
import { afterEach, describe, expect, it } from 'vitest';
import { silentLogger } from '../../server/logger.ts';
import { createRoomFactory } from '../../server/room-factory.ts';
import { RoomError } from '../../server/room.ts';
import { ByeReason, ErrorCode } from '../../shared/protocol/index.ts';
import { Simulation } from '../../shared/sim/simulation.ts';
import { scenarioList, startHarness, type Harness } from './harness.ts';
import { emptyScenario, stripScenario } from './test-scenarios.ts';

let h: Harness | null = null;
afterEach(async () => {
  await h?.close();
  h = null;
});

describe('RoomManager', () => {
  it('opens a room of a scenario when a client names the scenario as its room, and others join it by id', async () => {
    h = await startHarness({ scenarios: [stripScenario, emptyScenario] });
    const a = await h.join('ann', 'test-empty');
    expect(a.welcome?.roomId).toBe('test-empty');
    expect(a.welcome?.scenario.name).toBe('test-empty');
    const b = await h.join('bob', 'test-empty');
    expect(b.welcome?.roomId).toBe('test-empty');
    expect(b.playerId).toBe(2);
    expect(h.server.listRooms().map((r) => [r.id, r.scenario, r.clients])).toEqual([
      ['default', 'test-strip', 0],
      ['test-empty', 'test-empty', 2],
    ]);
    // Each room runs its own world: the default room did not tick (nobody there), the new one did.
    h.ticks(30);
    expect(h.room('test-empty').sim.tick).toBeGreaterThan(25);
    expect(h.room().sim.tick).toBe(0);
  });

  it('creates rooms with fresh ids from a scenario and parameters, and refuses unknown scenarios and bad parameters', async () => {
    h = await startHarness({ scenarios: [stripScenario, emptyScenario] });
    const r1 = await h.server.rooms.resolve({ scenario: 'test-strip', params: { boxes: 2 } });
    const r2 = await h.server.rooms.resolve({ scenario: 'test-strip' });
    expect(r1.id).not.toBe(r2.id);
    expect(r1.info()).toMatchObject({ scenario: 'test-strip', bodies: 4, params: { boxes: 2 } });
    await expect(h.server.rooms.resolve({ scenario: 'nope' })).rejects.toThrow(/unknown scenario "nope"/);
    await expect(h.server.rooms.resolve({ scenario: 'test-strip', params: { boxes: 9999 } })).rejects.toThrow(/boxes must be in \[0, 50\]/);
    await expect(h.server.rooms.resolve({ roomId: 'bad id!' })).rejects.toBeInstanceOf(RoomError);
  });

  it('shares one creation between concurrent requests for the same new room', async () => {
    h = await startHarness({ scenarios: [stripScenario, emptyScenario] });
    const [x, y] = await Promise.all([h.server.rooms.resolve({ roomId: 'arena', scenario: 'test-empty' }), h.server.rooms.resolve({ roomId: 'arena', scenario: 'test-empty' })]);
    expect(x).toBe(y);
    expect(h.server.listRooms()).toHaveLength(2);
  });

  it('closes a room that stays empty for the grace period, but never the default room', async () => {
    h = await startHarness({ scenarios: [stripScenario, emptyScenario] });
    const a = await h.join('ann', 'test-empty');
    a.send({ type: 'bye' });
    h.ticks(60 * 20); // 20 s: within the 30 s grace
    expect(h.server.rooms.get('test-empty')).toBeDefined();
    const b = await h.join('bob', 'test-empty'); // coming back cancels the countdown
    h.ticks(60 * 40);
    expect(h.server.rooms.get('test-empty')).toBeDefined();
    b.send({ type: 'bye' });
    h.ticks(60 * 31);
    expect(h.server.rooms.get('test-empty')).toBeUndefined();
    expect(h.server.rooms.get('default')).toBeDefined();
    expect(await h.server.metrics.registry.getSingleMetricAsString('taos_rooms')).toMatch(/taos_rooms 1$/);
  });

  it('refuses rooms past the rooms limit with a clear reason to the client', async () => {
    h = await startHarness({ scenarios: [stripScenario, emptyScenario], maxRooms: 2 });
    await h.join('ann', 'test-empty');
    const c = h.connect();
    c.hello('cal', 'another-room');
    await h.settle(() => c.closed !== null);
    expect(c.ofType('error')[0]?.code).toBe(ErrorCode.RoomNotFound);
    const d = h.connect();
    d.hello('dan', 'test-strip');
    await h.settle(() => d.closed !== null);
    expect(d.ofType('error')[0]).toMatchObject({ code: ErrorCode.ServerFull });
    expect(d.ofType('bye')[0]?.reason).toBe(ByeReason.ServerFull);
  });
});

describe('createRoomFactory', () => {
  it('refuses a new world with a clear Error when the shared WASM heap could not hold it', async () => {
    const factory = createRoomFactory({ scenarios: scenarioList([emptyScenario]), logger: silentLogger(), isolateRooms: false, minFreeHeapBytesForRoom: 200 * 1024 * 1024 });
    const first = await factory.createSimulation('test-empty', {}, 1); // the first world is always allowed
    await expect(factory.createSimulation('test-empty', {}, 1)).rejects.toThrow(/not enough physics memory for another room: [\d.]+ MiB free/);
    expect(factory.liveSimulations()).toBe(1);
    first.sim.destroy();
    expect(factory.liveSimulations()).toBe(0);
  });

  it('gives every room its own Jolt module, so rooms do not share a heap and build identical worlds', async () => {
    const factory = createRoomFactory({ scenarios: scenarioList([emptyScenario]), logger: silentLogger() });
    const builtA = await factory.createSimulation('test-empty', {}, 1);
    const builtB = await factory.createSimulation('test-empty', {}, 1);
    if (!(builtA.sim instanceof Simulation) || !(builtB.sim instanceof Simulation)) throw new Error('the factory builds Simulations');
    const a = builtA.sim;
    const b = builtB.sim;
    const freeBefore = a.world.freeHeapBytes();
    expect(b.world.jolt).not.toBe(a.world.jolt);
    expect(b.world.freeHeapBytes()).toBe(freeBefore); // the same fresh heap state, and b took nothing from a's heap
    expect(b.stateHash()).toBe(a.stateHash());
    a.destroy();
    b.destroy();
  });
});
