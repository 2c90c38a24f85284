// Tests for scenarios/character-course.ts (with course/*): layout, parameter checks, climbing the stairs and the
// ramp, the trigger opening and closing the door, the moving platform, shooting targets, state and determinism.
import { describe, expect, it } from 'vitest';
import { platformCentre, scenario } from '../../scenarios/character-course.ts';
import { DOOR_CLOSED, DOOR_TRAVEL_METRES } from '../../scenarios/course/door.ts';
import { TARGET_HOMES } from '../../scenarios/course/targets.ts';
import { CollisionLayer } from '../../shared/physics/index.ts';
import { expectParamsValidated, expectSeedDeterminism } from '../helpers/scenario-checks.ts';
import { Simulation } from '../../shared/sim/simulation.ts';
import type { SimEvent, TickInputRecord } from '../../shared/sim/types.ts';
import { ScenarioHarness } from '../helpers/scenario-harness.ts';
import { expectSimulationReplays } from '../helpers/scenario-sim.ts';

/** The body the scenario named `name`. */
function named(h: ScenarioHarness, name: string) {
  const body = h.scenarioBodyIds().map((id) => h.world.getBody(id)!).find((b) => b.name === name);
  if (!body) throw new Error(`no body named ${name}`);
  return body;
}

/** Walks player 1 from `from` with a command for `ticks` ticks; returns the highest feet y seen. */
function walk(h: ScenarioHarness, from: { x: number; y: number; z: number }, input: { moveX?: number; moveZ?: number; yaw?: number }, ticks: number): number {
  const c = h.controller(1);
  c.setPosition(from);
  h.setInput(1, input);
  let top = -Infinity;
  for (let i = 0; i < ticks; i++) {
    h.step();
    top = Math.max(top, c.position.y);
  }
  return top;
}

function bullet(h: ScenarioHarness, from: { x: number; y: number; z: number }, velocity: { x: number; y: number; z: number }) {
  return h.world.addSphere(0.05, from, {
    layer: CollisionLayer.Bullet,
    mask: CollisionLayer.World | CollisionLayer.Enemy | CollisionLayer.Prop,
    motionQuality: 'linearCast',
    massKg: 0.2,
    linearVelocity: velocity,
  });
}

/** A record for `tick` in which player 1 (joining at tick 0) moves with `input`. */
function record(tick: number, input: { moveX?: number; moveZ?: number; buttons?: number }): TickInputRecord {
  return {
    tick,
    leaves: [],
    joins: tick === 0 ? [{ playerId: 1, name: 'runner' }] : [],
    commands: [{ playerId: 1, input: { moveX: input.moveX ?? 0, moveZ: input.moveZ ?? 0, yaw: 0, pitch: 0, buttons: input.buttons ?? 0 } }],
  };
}

/** Steers player 1 (yaw 0: moveX is +x, moveZ is -z) to (x, z) on the ground plan; returns the events on the way. */
function goTo(sim: Simulation, x: number, z: number, maxTicks: number): SimEvent[] {
  const events: SimEvent[] = [];
  for (let i = 0; i < maxTicks; i++) {
    const me = sim.characters()[0];
    const dx = me ? x - me.position.x : 0;
    const dz = me ? z - me.position.z : 0;
    if (me && Math.abs(dx) < 0.2 && Math.abs(dz) < 0.2) return events;
    const axis = (d: number): number => (Math.abs(d) < 0.2 ? 0 : Math.max(-127, Math.min(127, Math.round(d * 150))));
    events.push(...sim.step(record(sim.tick, { moveX: axis(dx), moveZ: -axis(dz) })));
  }
  throw new Error(`player 1 did not reach (${x}, ${z}) in ${maxTicks} ticks: at ${JSON.stringify(sim.characters()[0]?.position)}`);
}

describe('character-course', () => {
  it('builds with defaults: 0.25 m stairs, ramp, wall, door, hidden trigger, platform, targets and crates', async () => {
    const h = await ScenarioHarness.create(scenario);
    try {
      for (let i = 1; i <= 8; i++) {
        const step = named(h, `stair ${i}`);
        const half = (step.shape as { halfExtents: { y: number } }).halfExtents.y;
        expect(step.position().y + half).toBeCloseTo(0.25 * i, 5);
      }
      expect(named(h, 'ramp').motion).toBe('static');
      expect(named(h, 'wall north').motion).toBe('static');
      expect(named(h, 'door').motion).toBe('kinematic');
      expect(named(h, 'platform').motion).toBe('kinematic');
      const trigger = named(h, 'door trigger');
      expect(trigger.isSensor).toBe(true);
      expect(trigger.layer).toBe(CollisionLayer.Trigger);
      expect(h.spawnOptions.get(trigger.id)?.hidden).toBe(true);
      expect(TARGET_HOMES.map((_, i) => named(h, `target ${i}`).motion)).toEqual(TARGET_HOMES.map(() => 'dynamic'));
      expect(h.dynamicBodies().filter((b) => b.name?.startsWith('crate '))).toHaveLength(6);
    } finally {
      h.destroy();
    }
  });

  it('rejects unknown and out-of-range parameters with a clear Error', async () => {
    await expectParamsValidated(scenario);
  });

  it('lets a character walk up the stairs and up the ramp onto the deck', async () => {
    const h = await ScenarioHarness.create(scenario);
    try {
      h.join(1);
      expect(walk(h, { x: -7, y: 0.05, z: 3.5 }, { moveZ: 127 }, 150)).toBeGreaterThan(1.95);
      expect(walk(h, { x: 7, y: 0.05, z: 6 }, { moveZ: 127 }, 150)).toBeGreaterThan(1.95);
      expect(h.controller(1).groundState).toBe('ground');
    } finally {
      h.destroy();
    }
  });

  it('opens the door when a player enters the trigger zone and closes it after they leave', async () => {
    const h = await ScenarioHarness.create(scenario, { params: { doorCloseDelayTicks: 30 } });
    try {
      const door = named(h, 'door');
      h.join(1);
      h.controller(1).setPosition({ x: 8, y: 0.05, z: 10 });
      h.run(60);
      expect(h.scenarioEvents('door')).toHaveLength(0);
      // Walk right (+x at yaw 0) into the zone, through the doorway and out the far side.
      h.setInput(1, { moveX: 127 });
      let opened = -1;
      for (let t = 0; t < 240 && opened < 0; t++) if (h.step().some((e) => e.type === 'scenario' && e.name === 'door' && e.value === 1)) opened = h.tick;
      expect(opened).toBeGreaterThan(0);
      h.run(60);
      expect(door.position().z).toBeCloseTo(DOOR_CLOSED.z - DOOR_TRAVEL_METRES, 2);
      h.run(120);
      expect(h.controller(1).position.x).toBeGreaterThan(18);
      h.setInput(1, {});
      h.run(120);
      expect(h.scenarioEvents('door').map((e) => e.value)).toEqual([1, 0]);
      expect(door.position().z).toBeCloseTo(DOOR_CLOSED.z, 3);
    } finally {
      h.destroy();
    }
  });

  it('ignores props that tumble into the trigger zone', async () => {
    const h = await ScenarioHarness.create(scenario);
    try {
      h.world.addBox({ x: 0.3, y: 0.3, z: 0.3 }, { x: 12, y: 1.5, z: 10 });
      h.run(90);
      expect(h.scenarioEvents('door')).toHaveLength(0);
      expect(named(h, 'door').position().z).toBeCloseTo(DOOR_CLOSED.z, 5);
    } finally {
      h.destroy();
    }
  });

  it('moves the platform along its path between the deck and the far ledge', async () => {
    const period = 120;
    const h = await ScenarioHarness.create(scenario, { params: { platformPeriodTicks: period } });
    try {
      const platform = named(h, 'platform');
      const zs: number[] = [];
      for (let t = 0; t < period; t++) {
        h.step();
        const p = platform.position();
        expect(p.z).toBeCloseTo(platformCentre(t + 1, period).z, 3);
        zs.push(p.z);
      }
      expect(Math.max(...zs)).toBeCloseTo(-7.5, 1);
      expect(Math.min(...zs)).toBeCloseTo(-12.5, 1);
      expect(zs[period - 1]).toBeCloseTo(zs[0], 1);
    } finally {
      h.destroy();
    }
  });

  it('reports a bullet hitting a target, the target falling and its reset', async () => {
    const h = await ScenarioHarness.create(scenario, { params: { targetResetTicks: 30 } });
    try {
      const home = TARGET_HOMES[0];
      const first = named(h, 'target 0').id;
      h.run(5);
      bullet(h, { x: 20, y: home.y, z: home.z }, { x: 40, y: 0, z: 0 });
      h.run(60);
      expect(h.scenarioEvents('targetHit').map((e) => e.value)).toEqual([0]);
      expect(h.scenarioEvents('targetDown').map((e) => e.value)).toEqual([0]);
      h.run(40);
      expect(h.scenarioEvents('targetReset').map((e) => e.value)).toEqual([0]);
      const again = named(h, 'target 0');
      expect(again.id).not.toBe(first);
      expect(again.position().y).toBeCloseTo(home.y, 1);
    } finally {
      h.destroy();
    }
  });

  it('does not count a thrown crate as a hit', async () => {
    const h = await ScenarioHarness.create(scenario);
    try {
      const home = TARGET_HOMES[1];
      h.world.addBox({ x: 0.1, y: 0.1, z: 0.1 }, { x: 22, y: home.y, z: home.z }, null, { linearVelocity: { x: 12, y: 1, z: 0 } });
      h.run(60);
      expect(h.scenarioEvents('targetHit')).toHaveLength(0);
    } finally {
      h.destroy();
    }
  });

  it('round-trips its scenario state and rejects a malformed one', async () => {
    const h = await ScenarioHarness.create(scenario);
    try {
      h.join(1);
      h.controller(1).setPosition({ x: 12, y: 0.05, z: 10 });
      h.run(20);
      const saved = h.instance.saveState!();
      expect(saved[1]).toBe(1); // the door is open
      h.run(10);
      h.instance.restoreState!(saved);
      expect(h.instance.saveState!()).toEqual(saved);
      expect(() => h.instance.restoreState!([...saved, 1])).toThrow(/unexpected trailing values/);
      expect(() => h.instance.restoreState!([4, 2, 0, 0, 0])).toThrow(/character-course: bad saved/);
    } finally {
      h.destroy();
    }
  });

  it('gives identical bodies for one seed and different ones for another', async () => {
    // The course itself draws nothing from the seed, so a seeded prop makes the runs comparable.
    const drive = (h: ScenarioHarness, tick: number): void => {
      if (tick === -1) {
        h.join(1);
        h.world.addSphere(0.3, { x: h.rng.range(-2, 2), y: 4, z: 6 });
      }
      if (tick === 10) h.setInput(1, { moveZ: 127, moveX: 40 });
    };
    await expectSeedDeterminism(scenario, {}, 90, drive);
  });
  it('opens the door for a player walking into the trigger in the Simulation', async () => {
    const sim = await Simulation.create({ scenario });
    try {
      const events = goTo(sim, 12, 10, 400);
      const door = events.filter((e) => e.type === 'scenario' && e.name === 'door');
      expect(door.map((e) => (e as { value: number }).value)).toEqual([1]);
      const trigger = sim.staticDescriptors().find((d) => d.hidden)!;
      expect(events.some((e) => e.type === 'sensorEnter' && e.sensorId === trigger.id && e.playerId === 1)).toBe(true);
    } finally {
      sim.destroy();
    }
  });

  it('carries a player standing on the moving platform across the gap in the Simulation', async () => {
    const sim = await Simulation.create({ scenario });
    try {
      goTo(sim, -7, 3, 200); // the foot of the stairs
      goTo(sim, -7, -4, 300); // up the stairs onto the deck
      expect(sim.characters()[0].position.y).toBeCloseTo(2, 1);
      goTo(sim, 0, -4, 300);
      // Wait until the platform (period 360 ticks) is about to reach the deck edge, walk onto it, then stand still.
      while (sim.tick % 360 !== 340) sim.step(record(sim.tick, {}));
      for (let i = 0; i < 55; i++) sim.step(record(sim.tick, { moveZ: 127 }));
      let farthest = 0;
      for (let i = 0; i < 150; i++) {
        sim.step(record(sim.tick, {}));
        farthest = Math.min(farthest, sim.characters()[0].position.z);
      }
      const me = sim.characters()[0];
      expect(farthest).toBeLessThan(-11);
      expect(me.position.y).toBeGreaterThan(1.9);
      expect(me.groundState).toBe('ground');
    } finally {
      sim.destroy();
    }
  });

  it('runs deterministically through the Simulation with bots, across checkpoint rollbacks', async () => {
    await expectSimulationReplays(scenario, {}, 150, 3);
  });
});
