// Tests of sensors: enter and exit fire exactly once per visit (falling, kinematic, sleeping, removed bodies),
// callbacks get the other body's handle, and each tick's events come sorted by (sensor id, other id).
import { describe, expect, it } from 'vitest';
import { CollisionLayer, type BodyHandle, type PhysicsWorld, type SensorEvent } from '../../../shared/physics/index.ts';
import { addGround, makeWorld, settle } from '../../helpers/physics.ts';

/** Steps `ticks` ticks and returns every event with the tick it came in. */
function collect(w: PhysicsWorld, ticks: number, each?: (tick: number) => void): Array<SensorEvent & { tick: number }> {
  const out: Array<SensorEvent & { tick: number }> = [];
  for (let t = 0; t < ticks; t++) {
    each?.(t);
    for (const e of w.stepFixed()) out.push({ ...e, tick: t });
  }
  return out;
}

describe('sensors', () => {
  it('fires enter once and exit once as a body falls through, handing callbacks the other body', async () => {
    const w = await makeWorld();
    const seen: string[] = [];
    const zone = w.addBox({ x: 1, y: 0.5, z: 1 }, { x: 0, y: 5, z: 0 }, null, {
      motion: 'static',
      sensor: {
        onEnter: (other) => seen.push(`enter ${(other as BodyHandle).id}`),
        onExit: (other) => seen.push(`exit ${(other as BodyHandle).id}`),
      },
    });
    const ball = w.addSphere(0.2, { x: 0, y: 8, z: 0 });
    const events = collect(w, 120);
    expect(events.map((e) => `${e.kind} ${e.sensorId} ${e.otherId}`)).toEqual([`enter ${zone.id} ${ball.id}`, `exit ${zone.id} ${ball.id}`]);
    expect(seen).toEqual([`enter ${ball.id}`, `exit ${ball.id}`]);
    expect(events[0].tick).toBeLessThan(events[1].tick);
    expect(w.sensorOverlaps(zone)).toEqual([]);
    w.destroy();
  });

  it('sees a kinematic body moved into a static sensor, and loses it once it moves out', async () => {
    const w = await makeWorld();
    const zone = w.addBox({ x: 1, y: 1, z: 1 }, { x: 0, y: 1, z: 0 }, null, { motion: 'static', isSensor: true });
    const mover = w.addBox({ x: 0.2, y: 0.2, z: 0.2 }, { x: -4, y: 1, z: 0 }, null, { motion: 'kinematic' });
    const events = collect(w, 90, () => {
      const p = mover.position();
      w.moveKinematic(mover, { x: p.x + 0.1, y: 1, z: 0 }, null);
    });
    expect(events.map((e) => e.kind)).toEqual(['enter', 'exit']);
    expect(events.every((e) => e.sensorId === zone.id && e.otherId === mover.id)).toBe(true);
    w.destroy();
  });

  it('keeps a body that falls asleep inside a static sensor inside, then exits once when it leaves', async () => {
    const w = await makeWorld();
    addGround(w);
    const plate = w.addBox({ x: 1, y: 0.5, z: 1 }, { x: 0, y: 0.5, z: 0 }, null, { motion: 'static', isSensor: true });
    const crate = w.addBox({ x: 0.2, y: 0.2, z: 0.2 }, { x: 0, y: 2, z: 0 });
    const events = collect(w, 30);
    settle(w, [crate]);
    expect(crate.isActive()).toBe(false);
    events.push(...collect(w, 120)); // asleep for two seconds: still inside
    expect(events.map((e) => e.kind)).toEqual(['enter']);
    expect(w.sensorOverlaps(plate)).toEqual([crate.id]);
    w.setLinearVelocity(crate, { x: 6, y: 0, z: 0 });
    const leaving = collect(w, 60);
    expect(leaving.map((e) => e.kind)).toEqual(['exit']);
    w.destroy();
  });

  it('detects a sleeping body when a sensor is created around it', async () => {
    const w = await makeWorld();
    addGround(w);
    const crate = w.addBox({ x: 0.2, y: 0.2, z: 0.2 }, { x: 3, y: 0.2, z: 0 });
    settle(w, [crate]);
    expect(crate.isActive()).toBe(false);
    const zone = w.addBox({ x: 1, y: 1, z: 1 }, { x: 3, y: 1, z: 0 }, null, { motion: 'static', isSensor: true });
    const events = collect(w, 5);
    expect(events.map((e) => `${e.kind} ${e.sensorId} ${e.otherId}`)).toEqual([`enter ${zone.id} ${crate.id}`]);
    w.destroy();
  });

  it('reports one exit for a body removed while inside, and none later', async () => {
    const w = await makeWorld();
    addGround(w);
    const exits: Array<BodyHandle | undefined> = [];
    const zone = w.addBox({ x: 1, y: 1, z: 1 }, { x: 0, y: 1, z: 0 }, null, { motion: 'static', sensor: { onExit: (o) => exits.push(o as BodyHandle) } });
    const crate = w.addBox({ x: 0.2, y: 0.2, z: 0.2 }, { x: 0, y: 0.5, z: 0 });
    expect(collect(w, 10).map((e) => e.kind)).toEqual(['enter']);
    w.removeBody(crate);
    const after = collect(w, 30);
    expect(after.map((e) => `${e.kind} ${e.sensorId} ${e.otherId}`)).toEqual([`exit ${zone.id} ${crate.id}`]);
    expect(after[0].tick).toBe(0);
    expect(exits.length).toBe(1);
    expect(exits[0]).toBeUndefined(); // the removed body has no handle any more
    expect(w.sensorOverlaps(zone)).toEqual([]);
    w.destroy();
  });

  it('reports the exits of everything inside a sensor that is removed', async () => {
    const w = await makeWorld();
    addGround(w);
    const zone = w.addBox({ x: 2, y: 1, z: 2 }, { x: 0, y: 1, z: 0 }, null, { motion: 'static', isSensor: true });
    const a = w.addSphere(0.2, { x: -0.5, y: 0.2, z: 0 });
    const b = w.addSphere(0.2, { x: 0.5, y: 0.2, z: 0 });
    expect(collect(w, 5).length).toBe(2);
    w.removeBody(zone);
    expect(collect(w, 20).map((e) => `${e.kind} ${e.sensorId} ${e.otherId}`)).toEqual([`exit ${zone.id} ${a.id}`, `exit ${zone.id} ${b.id}`]);
    w.destroy();
  });

  it('delivers each tick\'s events sorted by sensor id, then other id', async () => {
    const w = await makeWorld();
    // Three sensors side by side; bodies dropped so that several enter each sensor in the same tick.
    const zones = [0, 1, 2].map((i) => w.addBox({ x: 1, y: 0.5, z: 1 }, { x: i * 3, y: 2, z: 0 }, null, { motion: 'static', isSensor: true }));
    const bodies: BodyHandle[] = [];
    for (const i of [2, 0, 1]) for (const dx of [0.5, -0.5]) bodies.push(w.addSphere(0.2, { x: i * 3 + dx, y: 4, z: 0 }));
    const events = collect(w, 90);
    expect(events.length).toBe(12);
    const ticks = [...new Set(events.map((e) => e.tick))];
    for (const t of ticks) {
      const batch = events.filter((e) => e.tick === t);
      const sorted = [...batch].sort((x, y) => x.sensorId - y.sensorId || x.otherId - y.otherId);
      expect(batch).toEqual(sorted);
    }
    const enters = events.filter((e) => e.kind === 'enter');
    expect(new Set(enters.map((e) => e.tick)).size).toBe(1); // all six enter together
    expect(enters.map((e) => e.sensorId)).toEqual([zones[0].id, zones[0].id, zones[1].id, zones[1].id, zones[2].id, zones[2].id]);
    w.destroy();
  });

  it('ignores static bodies, other sensors and bodies whose mask leaves out the sensor\'s layer', async () => {
    const w = await makeWorld();
    addGround(w);
    w.addBox({ x: 0.3, y: 0.3, z: 0.3 }, { x: 0, y: 1, z: 0 }, null, { motion: 'static' });
    const zone = w.addBox({ x: 1.5, y: 1.5, z: 1.5 }, { x: 0, y: 1, z: 0 }, null, { motion: 'static', isSensor: true });
    const mover = w.addBox({ x: 0.5, y: 0.5, z: 0.5 }, { x: -4, y: 0.4, z: 0 }, null, { motion: 'kinematic', isSensor: true }); // dips into the ground
    const blind = w.addSphere(0.2, { x: 0.5, y: 3, z: 1.2 }, { mask: CollisionLayer.World });
    const seen = w.addSphere(0.2, { x: -0.5, y: 3, z: -1.2 }); // out of the moving sensor's path
    const events = collect(w, 80, () => {
      const p = mover.position();
      w.moveKinematic(mover, { x: p.x + 0.1, y: 0.4, z: 0 }, null);
    });
    expect(events.filter((e) => e.kind === 'enter').map((e) => `${e.sensorId} ${e.otherId}`)).toEqual([`${zone.id} ${seen.id}`]);
    expect(w.sensorOverlaps(zone)).toEqual([seen.id]);
    expect(blind.position().y).toBeCloseTo(0.2, 2); // it still lands on the ground (World is in its mask)
    w.destroy();
  });

  it('counts a compound body with several parts inside as one visit', async () => {
    const w = await makeWorld();
    const zone = w.addBox({ x: 2, y: 0.5, z: 2 }, { x: 0, y: 5, z: 0 }, null, { motion: 'static', isSensor: true });
    const part = { kind: 'sphere' as const, radius: 0.2 };
    const dumbbell = w.addCompound(
      [
        { shape: part, position: { x: -0.5, y: 0, z: 0 } },
        { shape: part, position: { x: 0.5, y: 0, z: 0 } },
      ],
      { x: 0, y: 8, z: 0 },
    );
    const events = collect(w, 120);
    expect(events.map((e) => `${e.kind} ${e.sensorId} ${e.otherId}`)).toEqual([`enter ${zone.id} ${dumbbell.id}`, `exit ${zone.id} ${dumbbell.id}`]);
    w.destroy();
  });

  it('makes a body a sensor with no collision response: things pass through it', async () => {
    const w = await makeWorld();
    w.addBox({ x: 2, y: 0.1, z: 2 }, { x: 0, y: 2, z: 0 }, null, { motion: 'static', isSensor: true });
    const ball = w.addSphere(0.2, { x: 0, y: 4, z: 0 });
    collect(w, 90);
    expect(ball.position().y).toBeLessThan(0);
    w.destroy();
  });

  it('runs every callback even when one throws, then reports the first failure', async () => {
    const w = await makeWorld();
    const calls: number[] = [];
    const zones = [0, 1, 2].map((i) =>
      w.addBox({ x: 1, y: 0.5, z: 1 }, { x: i * 3, y: 2, z: 0 }, null, {
        motion: 'static',
        sensor: {
          onEnter: () => {
            calls.push(i);
            if (i === 1) throw new Error('door jammed');
          },
        },
      }),
    );
    for (let i = 0; i < 3; i++) w.addSphere(0.2, { x: i * 3, y: 3, z: 0 });
    let thrown: Error | undefined;
    for (let t = 0; t < 60 && !thrown; t++) {
      try {
        w.stepFixed();
      } catch (err) {
        thrown = err as Error;
      }
    }
    expect(thrown?.message).toBe(`sensor ${zones[1].id}: its onEnter callback for body 5 threw: door jammed`);
    expect(calls).toEqual([0, 1, 2]);
    expect(w.sensorOverlaps(zones[2])).toEqual([6]); // the world kept its state
    w.stepFixed();
    w.destroy();
  });
});
