// Tests of Simulation: determinism within a process, creation order as input, record validation that applies
// nothing on error, the tick's events (joins, leaves, spawns, removals, sensors with player ids), descriptors.
import { describe, expect, it } from 'vitest';
import { CollisionLayer } from '../../../shared/physics/index.ts';
import { Button, quantizeInput } from '../../../shared/sim/input.ts';
import type { ScenarioDefinition } from '../../../shared/sim/scenario.ts';
import { Simulation } from '../../../shared/sim/simulation.ts';
import type { SimEvent } from '../../../shared/sim/types.ts';
import { botRecords, IDLE, idleTicks, makeSim, record, runHashes } from './helpers/sim-helpers.ts';
import { testArena, testArenaReversed, ZONE_CENTRE } from './helpers/test-scenarios.ts';

describe('simulation', () => {
  it('gives identical per-tick hashes when the same session runs twice in one process', async () => {
    const records = botRecords(150, { bots: 3, leaveTicks: [-1, 90, -1] });
    const a = await makeSim();
    const b = await makeSim();
    const ha = runHashes(a, records);
    const hb = runHashes(b, records);
    expect(ha).toEqual(hb);
    expect(new Set(ha).size).toBe(ha.length);
    a.destroy();
    b.destroy();
  });

  it('treats creation order as input: the same scene built in reverse order hashes differently', async () => {
    const a = await makeSim(testArena);
    const b = await makeSim(testArenaReversed);
    idleTicks(a, 1);
    idleTicks(b, 1);
    expect(a.stateHash()).not.toBe(b.stateHash());
    const d = a.firstDivergence(b);
    expect(d?.part).toBe('body');
    expect(d?.bodyId).toBe(1);
    a.destroy();
    b.destroy();
  });

  it('starts at tick 0 and counts the ticks it applied', async () => {
    const sim = await makeSim();
    expect(sim.tick).toBe(0);
    idleTicks(sim, 3);
    expect(sim.tick).toBe(3);
    sim.destroy();
  });

  it('rejects a record for the wrong tick and changes nothing', async () => {
    const sim = await makeSim();
    idleTicks(sim, 2);
    const before = sim.stateHash();
    expect(() => sim.step(record(5))).toThrow(/simulation is at tick 2/);
    expect(sim.tick).toBe(2);
    expect(sim.stateHash()).toBe(before);
    sim.destroy();
  });

  it('rejects NaN and wrongly typed commands before anything reaches Jolt, then carries on as if they never came', async () => {
    const join = record(0, { joins: [{ playerId: 1, name: 'p' }] });
    const walk = (t: number) => record(t, { commands: [{ playerId: 1, input: { ...IDLE, moveZ: 127 } }] });
    const clean = await makeSim();
    const hashesClean = runHashes(clean, [join, walk(1), walk(2), walk(3)]);
    const sim = await makeSim();
    runHashes(sim, [join, walk(1)]);
    const before = sim.stateHash();
    const bodiesBefore = sim.readBodyStates().states.slice();
    const bad: unknown[] = [{ ...IDLE, moveX: NaN }, { ...IDLE, yaw: 'north' }, { ...IDLE, buttons: -1 }, { ...IDLE, pitch: Infinity }, undefined];
    for (const input of bad) {
      expect(() => sim.step({ tick: 2, leaves: [], joins: [{ playerId: 2, name: 'late' }], commands: [{ playerId: 1, input } as never] })).toThrow(/command of player 1 is invalid/);
    }
    expect(sim.tick).toBe(2);
    expect(sim.playerIds()).toEqual([1]);
    expect(sim.stateHash()).toBe(before);
    expect(sim.readBodyStates().states).toEqual(bodiesBefore);
    expect(runHashes(sim, [walk(2), walk(3)])).toEqual(hashesClean.slice(2));
    clean.destroy();
    sim.destroy();
  });

  it('rejects unknown and duplicate player ids with a clear error', async () => {
    const sim = await makeSim();
    expect(() => sim.step(record(0, { commands: [{ playerId: 9, input: IDLE }] }))).toThrow(/player 9, who is not in the game/);
    expect(() => sim.step(record(0, { leaves: [9] }))).toThrow(/player 9 cannot leave/);
    expect(() => sim.step(record(0, { joins: [{ playerId: 1, name: 'a' }, { playerId: 1, name: 'b' }] }))).toThrow(/appears twice|cannot join/);
    sim.step(record(0, { joins: [{ playerId: 1, name: 'a' }] }));
    expect(() => sim.step(record(1, { joins: [{ playerId: 1, name: 'again' }] }))).toThrow(/player 1 cannot join, it is already in the game/);
    sim.destroy();
  });

  it('reports joins, leaves, spawns, removals and scenario events stamped with their tick', async () => {
    const sim = await makeSim(testArena, { spawnEvery: 5 });
    const events: SimEvent[] = [];
    const records = [record(0, { joins: [{ playerId: 4, name: 'dee' }] }), ...Array.from({ length: 30 }, (_, i) => record(i + 1)), record(31, { leaves: [4] })];
    runHashes(sim, records, events);
    const joined = events.find((e) => e.type === 'playerJoined');
    expect(joined).toMatchObject({ type: 'playerJoined', tick: 0, playerId: 4, name: 'dee' });
    expect(events.find((e) => e.type === 'playerLeft')).toEqual({ type: 'playerLeft', tick: 31, playerId: 4 });
    const spawns = events.filter((e) => e.type === 'bodySpawned');
    const removals = events.filter((e) => e.type === 'bodyRemoved');
    expect(spawns.map((e) => e.tick)).toEqual([0, 5, 10, 15, 20, 25, 30]);
    expect(removals.map((e) => e.tick)).toEqual([20, 25, 30]);
    for (const e of removals) expect(sim.bodyDescriptor((e as { bodyId: number }).bodyId)).toBeUndefined();
    sim.destroy();
  });

  it('delivers sensor events naming the player whose character entered and left the zone', async () => {
    const sim = await makeSim(testArena, { spawnEvery: 0 });
    const yaw = Math.atan2(-(ZONE_CENTRE.x - 0), -(ZONE_CENTRE.z - 4));
    const walk = quantizeInput(0, 1, yaw, 0, 0);
    const events: SimEvent[] = [];
    runHashes(sim, [record(0, { joins: [{ playerId: 3, name: 'walker' }], commands: [{ playerId: 3, input: walk }] }), ...Array.from({ length: 170 }, (_, i) => record(i + 1))], events);
    const zoneId = sim.descriptors().find((d) => d.hidden)!.id;
    const bodyId = sim.characters()[0].bodyId;
    const enter = events.find((e) => e.type === 'sensorEnter');
    const exit = events.find((e) => e.type === 'sensorExit');
    expect(enter).toMatchObject({ type: 'sensorEnter', sensorId: zoneId, bodyId, playerId: 3 });
    expect(exit).toMatchObject({ type: 'sensorExit', sensorId: zoneId, bodyId, playerId: 3 });
    expect(exit!.tick).toBeGreaterThan(enter!.tick);
    expect(events.find((e) => e.type === 'scenario')).toEqual({ type: 'scenario', tick: enter!.tick, name: 'zoneVisit', value: 3 });
    sim.destroy();
  });

  it("repeats a player's last command on ticks that bring none", async () => {
    const cmd = { ...IDLE, moveZ: 127, buttons: Button.Sprint };
    const every = await makeSim(testArena, { spawnEvery: 0 });
    const once = await makeSim(testArena, { spawnEvery: 0 });
    const join = { joins: [{ playerId: 1, name: 'p' }], commands: [{ playerId: 1, input: cmd }] };
    const a = runHashes(every, [record(0, join), ...Array.from({ length: 40 }, (_, i) => record(i + 1, { commands: [{ playerId: 1, input: cmd }] }))]);
    const b = runHashes(once, [record(0, join), ...Array.from({ length: 40 }, (_, i) => record(i + 1))]);
    expect(b).toEqual(a);
    expect(once.characters()[0].position.z).toBeLessThan(0);
    every.destroy();
    once.destroy();
  });

  it('describes every body for clients: scene geometry, characters with their player, spawned bodies', async () => {
    const sim = await makeSim(testArena, { boxes: 4, spawnEvery: 1 });
    sim.step(record(0, { joins: [{ playerId: 8, name: 'eve' }] }));
    const statics = sim.staticDescriptors();
    expect(statics.map((d) => d.motion)).toEqual(['static', 'static']);
    expect(statics[0].shape).toEqual({ kind: 'box', halfExtents: { x: 20, y: 0.5, z: 20 } });
    const character = sim.bodyDescriptor(sim.characters()[0].bodyId)!;
    expect(character).toMatchObject({ playerId: 8, motion: 'kinematic', hidden: false });
    expect(character.shape.kind).toBe('compound');
    const all = sim.descriptors();
    expect(all.map((d) => d.id)).toEqual(Array.from(sim.readBodyStates().ids));
    const sphere = all.find((d) => d.shape.kind === 'sphere')!;
    expect(sphere.color).toEqual([0.2, 0.6, 0.9]);
    expect(sim.bodyDescriptor(99999)).toBeUndefined();
    sim.destroy();
  });

  it('reports characters by player id with position, velocity, yaw and ground state', async () => {
    const sim = await makeSim();
    sim.step(record(0, { joins: [{ playerId: 2, name: 'a' }, { playerId: 5, name: 'b' }] }));
    idleTicks(sim, 20);
    const chars = sim.characters();
    expect(chars.map((c) => c.playerId)).toEqual([2, 5]);
    expect(chars[0].position).toEqual({ x: expect.closeTo(0, 2), y: expect.closeTo(0, 1), z: expect.closeTo(4, 2) });
    expect(chars[1].position.x).toBeCloseTo(1.5, 2);
    expect(chars[0].groundState).toBe('ground');
    sim.destroy();
  });

  it('rejects bad creation options with clear errors', async () => {
    await expect(Simulation.create({ scenario: testArena, params: { boxes: -1 } })).rejects.toThrow(/boxes must be in \[0, 400\]/);
    await expect(Simulation.create({ scenario: testArena, params: { nope: 1 } })).rejects.toThrow(/unknown parameter "nope"/);
    await expect(Simulation.create({ scenario: testArena, seed: -3 })).rejects.toThrow(/seed must be/);
    const badBounds: ScenarioDefinition = { ...testArena, bounds: { min: { x: 0, y: 0, z: 0 }, max: { x: 0, y: 1, z: 1 } } };
    await expect(Simulation.create({ scenario: badBounds })).rejects.toThrow(/bounds must be finite/);
  });

  it('refuses a scenario that adds bodies behind its back, and recovers from a checkpoint', async () => {
    let sneaky = false;
    const def: ScenarioDefinition = {
      ...testArena,
      build: (ctx) => {
        const inner = testArena.build(ctx);
        return { ...inner, onTick: (c) => (sneaky ? void c.world.addSphere(0.2, { x: 0, y: 3, z: 0 }, { layer: CollisionLayer.Prop }) : inner.onTick?.(c)) };
      },
    };
    const clean = await makeSim(def);
    idleTicks(clean, 8);
    const sim = await makeSim(def);
    idleTicks(sim, 3);
    const cp = sim.saveCheckpoint();
    sneaky = true;
    expect(() => idleTicks(sim, 1)).toThrow(/changed bodies through ctx.world directly/);
    expect(() => idleTicks(sim, 1)).toThrow(/must be restored from a checkpoint/);
    expect(() => sim.saveCheckpoint()).toThrow(/failed at tick 3/);
    sneaky = false;
    sim.restoreCheckpoint(cp);
    idleTicks(sim, 5);
    expect(sim.stateHash()).toBe(clean.stateHash());
    cp.dispose();
    sim.destroy();
    clean.destroy();
  });
  it('reads body states that match the world after every step and after a checkpoint restore', async () => {
    const sim = await makeSim();
    const copy = (r: ReturnType<Simulation['readBodyStates']>) => ({ ids: Array.from(r.ids), states: Array.from(r.states), flags: Array.from(r.flags) });
    const records = botRecords(40, { bots: 2 });
    for (const r of records.slice(0, 20)) sim.step(r);
    const cp = sim.saveCheckpoint();
    const atSave = copy(sim.world.readBodyStates());
    const hashAtSave = sim.stateHash();
    for (const r of records.slice(20)) {
      sim.step(r);
      const hash = sim.stateHash(); // reads the bodies first; the read below must still be this tick's
      expect(copy(sim.readBodyStates())).toEqual(copy(sim.world.readBodyStates()));
      expect(hash).not.toBe(hashAtSave);
    }
    expect(copy(sim.readBodyStates())).not.toEqual(atSave);
    sim.restoreCheckpoint(cp);
    expect(copy(sim.readBodyStates())).toEqual(atSave);
    expect(sim.stateHash()).toBe(hashAtSave);
    cp.dispose();
    sim.destroy();
  });
});
