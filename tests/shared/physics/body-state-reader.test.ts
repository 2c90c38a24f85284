// Tests of the bulk body read: the same values as each handle's getters, ids ascending, flags per motion kind and
// activity, and a rebuilt order after bodies come and go.
import { describe, expect, it } from 'vitest';
import { BodyFlag, BODY_STATE_STRIDE, CharacterController, FastStateBuffer } from '../../../shared/physics/index.ts';
import { BodyStateReader, type BodyStates } from '../../../shared/physics/body-state-reader.ts';
import type { BodyHandle, PhysicsWorld } from '../../../shared/physics/index.ts';
import { makeWorld, run } from '../../helpers/physics.ts';

/** A deterministic stream of numbers in [0, 1) (the test must replay the same spawns and removals). */
function lcg(seed: number): () => number {
  let s = seed >>> 0;
  return () => {
    s = (Math.imul(s, 1664525) + 1013904223) >>> 0;
    return s / 2 ** 32;
  };
}

/** A copy of a bulk read (its arrays are views that the next read overwrites). */
function copyOf(s: BodyStates): { ids: number[]; states: number[]; flags: number[] } {
  return { ids: Array.from(s.ids), states: Array.from(s.states), flags: Array.from(s.flags) };
}

/** What a reader rebuilding the whole table reads from the world now. */
function fullRebuild(w: PhysicsWorld): ReturnType<typeof copyOf> {
  const ids = w.bodyIds();
  const records = new Map(ids.map((id) => [id, w.getBody(id)!] as const));
  return copyOf(new BodyStateReader(w.jolt).read(ids, records));
}

describe('body-state-reader', () => {
  it("reads exactly what each body's getters return, in ascending id order", async () => {
    const w = await makeWorld();
    w.addBox({ x: 10, y: 0.5, z: 10 }, { x: 0, y: -0.5, z: 0 }, null, { motion: 'static' });
    for (let i = 0; i < 20; i++) w.addConvexHull([0, 0, 0, 0.5, 0, 0, 0, 0.7, 0, 0, 0, 0.4], { x: i * 0.3 - 3, y: 1 + (i % 3), z: 0 }, null, { angularVelocity: { x: i, y: 0, z: 1 } });
    run(w, 30);
    const s = w.readBodyStates();
    expect(Array.from(s.ids)).toEqual(w.bodyIds());
    for (let i = 0; i < s.count; i++) {
      const h = w.getBody(s.ids[i])!;
      const p = h.position();
      const q = h.rotation();
      const v = h.linearVelocity();
      const a = h.angularVelocity();
      const expected = [p.x, p.y, p.z, q.x, q.y, q.z, q.w, v.x, v.y, v.z, a.x, a.y, a.z].map((x) => Math.fround(x));
      expect(Array.from(s.states.subarray(i * BODY_STATE_STRIDE, (i + 1) * BODY_STATE_STRIDE))).toEqual(expected);
    }
    w.destroy();
  });

  it('flags static, dynamic, kinematic, sensor, character and active bodies', async () => {
    const w = await makeWorld();
    const ground = w.addBox({ x: 10, y: 0.5, z: 10 }, { x: 0, y: -0.5, z: 0 }, null, { motion: 'static' });
    const falling = w.addSphere(0.3, { x: 0, y: 3, z: 0 });
    const sleeper = w.addSphere(0.3, { x: 3, y: 0.3, z: 0 });
    const lift = w.addBox({ x: 1, y: 0.1, z: 1 }, { x: -3, y: 1, z: 0 }, null, { motion: 'kinematic' });
    const zone = w.addBox({ x: 1, y: 1, z: 1 }, { x: 6, y: 1, z: 0 }, null, { motion: 'static', isSensor: true });
    const ch = new CharacterController(w, { position: { x: -6, y: 0, z: 0 } });
    run(w, 90);
    w.setLinearVelocity(falling, { x: 0, y: 2, z: 0 });
    const s = w.readBodyStates();
    const flagOf = (id: number) => s.flags[Array.from(s.ids).indexOf(id)];
    expect(flagOf(ground.id)).toBe(BodyFlag.Static);
    expect(flagOf(falling.id)).toBe(BodyFlag.Dynamic | BodyFlag.Active);
    expect(flagOf(sleeper.id)).toBe(BodyFlag.Dynamic);
    expect(flagOf(lift.id) & ~BodyFlag.Active).toBe(BodyFlag.Kinematic);
    expect(flagOf(zone.id)).toBe(BodyFlag.Static | BodyFlag.Sensor);
    expect(flagOf(ch.body!.id) & BodyFlag.Character).toBe(BodyFlag.Character);
    ch.destroy();
    w.destroy();
  });

  it('follows bodies added and removed between reads', async () => {
    const w = await makeWorld();
    const a = w.addSphere(0.2, { x: 0, y: 0, z: 0 });
    const b = w.addSphere(0.2, { x: 1, y: 0, z: 0 });
    expect(Array.from(w.readBodyStates().ids)).toEqual([a.id, b.id]);
    w.removeBody(a);
    const c = w.addSphere(0.2, { x: 2, y: 5, z: 0 });
    const s = w.readBodyStates();
    expect(Array.from(s.ids)).toEqual([b.id, c.id]);
    expect(s.states[BODY_STATE_STRIDE + 1]).toBe(5);
    w.destroy();
  });

  it('keeps the same table as a full rebuild over random spawns and removals in the world', async () => {
    const w = await makeWorld();
    w.addBox({ x: 20, y: 0.5, z: 20 }, { x: 0, y: -0.5, z: 0 }, null, { motion: 'static' });
    const rand = lcg(14);
    const live: BodyHandle[] = [];
    w.readBodyStates(); // the first read builds the table; every change after it is incremental
    for (let round = 0; round < 40; round++) {
      const spawns = Math.floor(rand() * 12);
      for (let i = 0; i < spawns; i++) {
        const pos = { x: rand() * 20 - 10, y: 1 + rand() * 5, z: rand() * 20 - 10 };
        live.push(rand() < 0.5 ? w.addSphere(0.2, pos) : w.addBox({ x: 0.2, y: 0.2, z: 0.2 }, pos, null, { motion: rand() < 0.2 ? 'kinematic' : 'dynamic' }));
      }
      const removals = Math.floor(rand() * 8);
      for (let i = 0; i < removals && live.length > 0; i++) w.removeBody(live.splice(Math.floor(rand() * live.length), 1)[0]);
      run(w, 2);
      expect(copyOf(w.readBodyStates()), `round ${round}`).toEqual(fullRebuild(w));
    }
    w.destroy();
  });

  it('inserts bodies added out of id order at their place, as a full rebuild orders them', async () => {
    const w = await makeWorld();
    const bodies = Array.from({ length: 60 }, (_, i) => w.addSphere(0.2, { x: i, y: 2, z: 0 }));
    const rand = lcg(7);
    const reader = new BodyStateReader(w.jolt);
    reader.read([], new Map()); // an empty table: from here on only add and remove change it
    const inReader = new Set<BodyHandle>();
    const order = bodies.slice().sort(() => rand() - 0.5);
    for (const h of order) {
      reader.add(h);
      inReader.add(h);
      if (rand() < 0.3) {
        const gone = [...inReader][Math.floor(rand() * inReader.size)];
        reader.remove(gone);
        inReader.delete(gone);
      }
      const ids = [...inReader].map((b) => b.id).sort((a, b) => a - b);
      const records = new Map([...inReader].map((b) => [b.id, b] as const));
      expect(copyOf(reader.read(ids, records))).toEqual(copyOf(new BodyStateReader(w.jolt).read(ids, records)));
    }
    w.destroy();
  });

  it('lists awake bodies outside a box, skipping static and sleeping ones', async () => {
    const w = await makeWorld();
    const ground = w.addBox({ x: 10, y: 0.5, z: 10 }, { x: 0, y: -0.5, z: 0 }, null, { motion: 'static' });
    const farStatic = w.addBox({ x: 1, y: 1, z: 1 }, { x: 50, y: 0, z: 0 }, null, { motion: 'static' });
    const sleeper = w.addSphere(0.3, { x: 3, y: 0.3, z: 0 });
    const faller = w.addSphere(0.3, { x: -3, y: 0.3, z: 0 });
    run(w, 120);
    expect(sleeper.isActive()).toBe(false);
    const min = { x: -5, y: -1, z: -5 };
    const max = { x: 5, y: 5, z: 5 };
    expect(w.awakeBodiesOutside(min, max)).toEqual([]);
    w.setPosition(faller, { x: -30, y: 0.3, z: 0 });
    expect(w.awakeBodiesOutside(min, max)).toEqual([faller.id]);
    expect([ground.id, farStatic.id, sleeper.id].some((id) => w.awakeBodiesOutside(min, max).includes(id))).toBe(false);
    w.destroy();
  });
  it('reads again a sleeping or static body moved through the world, and every body after a restored state', async () => {
    const w = await makeWorld();
    const ground = w.addBox({ x: 10, y: 0.5, z: 10 }, { x: 0, y: -0.5, z: 0 }, null, { motion: 'static' });
    const sleeper = w.addSphere(0.3, { x: 3, y: 0.3, z: 0 });
    const buffer = new FastStateBuffer(w.jolt);
    run(w, 120);
    expect(sleeper.isActive()).toBe(false);
    buffer.saveWorld(w);
    w.readBodyStates();
    // A static body teleports without waking; a velocity too small to wake a body still changes it.
    w.setPosition(ground, { x: 1, y: -0.5, z: 0 });
    w.setLinearVelocity(sleeper, { x: 1e-7, y: 0, z: 0 });
    expect(sleeper.isActive()).toBe(false);
    expect(copyOf(w.readBodyStates())).toEqual(fullRebuild(w));
    expect(w.readBodyStates().states[0]).toBe(1);
    buffer.restoreWorld(w);
    expect(copyOf(w.readBodyStates())).toEqual(fullRebuild(w));
    expect(w.readBodyStates().states[0]).toBe(0);
    buffer.dispose();
    w.destroy();
  });
});

