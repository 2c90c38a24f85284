// Tests of deterministic Jolt BodyIDs: the same sequence of creations and removals (bodies and character inner
// bodies alike) gives the same Jolt ids in every world, and a body can be recreated at a saved id.
import { describe, expect, it } from 'vitest';
import { CharacterController, type PhysicsWorld } from '../../../shared/physics/index.ts';
import { makeWorld } from '../../helpers/physics.ts';

/** Builds and tears down bodies and characters in a fixed pattern; returns every Jolt id handed out, in order. */
function churn(w: PhysicsWorld): number[] {
  const ids: number[] = [];
  const bodies = [];
  for (let round = 0; round < 300; round++) {
    const b = w.addSphere(0.1, { x: round % 10, y: 0, z: 0 });
    ids.push(b.joltId);
    expect(b.joltId).toBe(b.raw.GetID().GetIndexAndSequenceNumber());
    bodies.push(b);
    const ch = new CharacterController(w, { position: { x: 0, y: 0, z: round } });
    ids.push(ch.body!.joltId);
    if (round % 3 === 0) w.removeBody(bodies.shift()!);
    ch.destroy(); // its inner body's slot is reused by a later body or character
  }
  return ids;
}

describe('body-slots', () => {
  it('hands out the same Jolt ids in every world given the same creations and removals', async () => {
    const a = await makeWorld();
    const b = await makeWorld();
    const idsA = churn(a);
    expect(churn(b)).toEqual(idsA);
    expect(new Set(idsA).size).toBe(idsA.length); // a reused slot comes back with a new sequence number…
    expect(new Set(idsA.map((id) => id & 0x7fffff)).size).toBeLessThan(idsA.length / 2); // …and slots really were reused
    a.destroy();
    b.destroy();
  });

  it('recreates a body at a saved stable id and Jolt id, refusing one that is taken', async () => {
    const w = await makeWorld();
    const first = w.addSphere(0.1, { x: 0, y: 0, z: 0 });
    const saved = { id: first.id, joltId: first.joltId };
    w.removeBody(first);
    const back = w.addShape({ kind: 'sphere', radius: 0.1 }, { x: 0, y: 0, z: 0 }, null, {}, saved);
    expect(back.id).toBe(saved.id);
    expect(back.joltId).toBe(saved.joltId);
    expect(() => w.addShape({ kind: 'sphere', radius: 0.1 }, { x: 0, y: 0, z: 0 }, null, {}, saved)).toThrow(/stable id 1 is already in use/);
    expect(w.bodyCount).toBe(1);
    w.destroy();
  });
});
