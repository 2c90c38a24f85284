// Tests of constraints: a 5-link pendulum keeps its link lengths, hinge/distance/slider links do what they say,
// settings are always consumed, and bad pairs throw clear Errors.
import { describe, expect, it } from 'vitest';
import { distanceLink, hingeLink, sliderLink, type BodyHandle } from '../../../shared/physics/index.ts';
import { addGround, distance, makeWorld, rotate, run } from '../../helpers/physics.ts';

describe('constraints', () => {
  it('keeps every link of a 5-link pendulum within 1% of its length while it swings', async () => {
    const w = await makeWorld();
    const anchor = w.addBox({ x: 0.1, y: 0.1, z: 0.1 }, { x: 0, y: 10, z: 0 }, null, { motion: 'static' });
    // Released 60° from the vertical, so the chain swings through and whips at the bottom.
    const dir = { x: Math.sqrt(3) / 2, y: -0.5 };
    const links: BodyHandle[] = [];
    let prev = anchor;
    for (let i = 1; i <= 5; i++) {
      const ball = w.addSphere(0.15, { x: dir.x * i * 0.8, y: 10 + dir.y * i * 0.8, z: 0 }, { massKg: 1 });
      w.pointLink(prev, ball, prev.position()); // each ball swings about the centre of the one above
      links.push(ball);
      prev = ball;
    }
    // Link length: 0.8 m between consecutive centres.
    let worst = 0;
    let leftmost = Infinity;
    for (let t = 0; t < 300; t++) {
      w.stepFixed();
      worst = Math.max(worst, Math.abs(distance(anchor.position(), links[0].position()) - 0.8) / 0.8);
      for (let i = 1; i < 5; i++) worst = Math.max(worst, Math.abs(distance(links[i - 1].position(), links[i].position()) - 0.8) / 0.8);
      leftmost = Math.min(leftmost, links[4].position().x);
    }
    expect(leftmost).toBeLessThan(-2); // it really swung through to the other side
    expect(worst).toBeLessThan(0.01);
    expect(w.constraintCount).toBe(5);
    w.destroy();
  });

  it('hinges a door about its vertical axis, within its limits', async () => {
    const w = await makeWorld();
    const post = w.addBox({ x: 0.05, y: 1, z: 0.05 }, { x: 0, y: 1, z: 0 }, null, { motion: 'static' });
    // The door's near edge is 5 cm clear of the post; the hinge line runs up that edge.
    const door = w.addBox({ x: 0.5, y: 1, z: 0.05 }, { x: 0.6, y: 1.05, z: 0 }, null, { massKg: 20, angularDamping: 0 });
    hingeLink(w, post, door, { x: 0.1, y: 1, z: 0 }, { x: 0, y: 1, z: 0 }, { minRadians: -Math.PI / 4, maxRadians: Math.PI / 4 });
    w.addImpulse(door, { x: 0, y: 0, z: -30 }, { x: 1.1, y: 1, z: 0 }); // shove the free edge
    let maxAngle = 0;
    for (let t = 0; t < 120; t++) {
      w.stepFixed();
      const q = door.rotation();
      expect(Math.abs(q.x) + Math.abs(q.z)).toBeLessThan(0.01); // it only turns about y
      maxAngle = Math.max(maxAngle, Math.abs(2 * Math.atan2(q.y, q.w)));
      // The hinge line stays put: the door's near edge stays on it.
      const edge = rotate(q, { x: -0.5, y: 0, z: 0 });
      const p = door.position();
      expect(distance({ x: p.x + edge.x, y: 0, z: p.z + edge.z }, { x: 0.1, y: 0, z: 0 })).toBeLessThan(0.01);
    }
    expect(maxAngle).toBeGreaterThan(Math.PI / 4 - 0.05); // it reached the stop…
    expect(maxAngle).toBeLessThan(Math.PI / 4 + 0.05); // …and no further
    expect(door.position().y).toBeCloseTo(1.05, 1); // held up by the hinge, not fallen
    w.destroy();
  });

  it('keeps a distance link between its minimum and maximum', async () => {
    const w = await makeWorld({ gravity: { x: 0, y: 0, z: 0 } });
    const a = w.addSphere(0.1, { x: 0, y: 0, z: 0 }, { linearDamping: 0 });
    const b = w.addSphere(0.1, { x: 1.5, y: 0, z: 0 }, { linearDamping: 0 });
    distanceLink(w, a, b, a.position(), b.position(), { minDistance: 1, maxDistance: 2 });
    w.setLinearVelocity(b, { x: 5, y: 0, z: 0 });
    let longest = 0;
    for (let t = 0; t < 60; t++) {
      w.stepFixed();
      longest = Math.max(longest, distance(a.position(), b.position()));
    }
    expect(longest).toBeGreaterThan(1.95);
    expect(longest).toBeLessThan(2.02);
    w.setLinearVelocity(b, { x: -5, y: 0, z: 0 });
    w.setLinearVelocity(a, { x: 5, y: 0, z: 0 });
    let shortest = Infinity;
    for (let t = 0; t < 60; t++) {
      w.stepFixed();
      shortest = Math.min(shortest, distance(a.position(), b.position()));
    }
    expect(shortest).toBeGreaterThan(0.98);
    w.destroy();
  });

  it('holds a distance link at its current length when no range is given', async () => {
    const w = await makeWorld();
    const hook = w.addBox({ x: 0.1, y: 0.1, z: 0.1 }, { x: 0, y: 5, z: 0 }, null, { motion: 'static' });
    const weight = w.addSphere(0.2, { x: 1.2, y: 5, z: 0 });
    distanceLink(w, hook, weight, hook.position(), weight.position());
    for (let t = 0; t < 120; t++) {
      w.stepFixed();
      expect(Math.abs(distance(hook.position(), weight.position()) - 1.2)).toBeLessThan(0.012);
    }
    expect(weight.position().y).toBeLessThan(4.5); // swung down, on its 1.2 m rope
    w.destroy();
  });

  it('lets a slider move only along its axis, stopped by its limits', async () => {
    const w = await makeWorld({ gravity: { x: 0, y: 0, z: 0 } });
    const rail = w.addBox({ x: 2, y: 0.05, z: 0.05 }, { x: 0, y: 1, z: 0 }, null, { motion: 'static' });
    const carriage = w.addBox({ x: 0.1, y: 0.1, z: 0.1 }, { x: 0, y: 1.2, z: 0 }, null, { linearDamping: 0 });
    sliderLink(w, rail, carriage, { x: 0, y: 1.2, z: 0 }, { x: 1, y: 0, z: 0 }, { minMetres: -0.5, maxMetres: 1 });
    w.setLinearVelocity(carriage, { x: 2, y: 3, z: -4 });
    w.setAngularVelocity(carriage, { x: 1, y: 2, z: 3 });
    let furthest = 0;
    for (let t = 0; t < 90; t++) {
      w.stepFixed();
      const p = carriage.position();
      expect(Math.abs(p.y - 1.2)).toBeLessThan(0.01);
      expect(Math.abs(p.z)).toBeLessThan(0.01);
      furthest = Math.max(furthest, p.x);
    }
    expect(furthest).toBeGreaterThan(0.95);
    expect(furthest).toBeLessThan(1.03);
    const q = carriage.rotation();
    expect(Math.abs(q.w)).toBeGreaterThan(0.9999); // no rotation either
    w.destroy();
  });

  it('throws a clear Error for bad pairs and bad parameters, and leaves no constraint behind', async () => {
    const w = await makeWorld();
    const ground = addGround(w);
    const wall = w.addBox({ x: 1, y: 1, z: 1 }, { x: 5, y: 1, z: 0 }, null, { motion: 'static' });
    const a = w.addSphere(0.2, { x: 0, y: 1, z: 0 });
    const pivot = { x: 0, y: 1, z: 0 };
    expect(() => w.pointLink(a, a, pivot)).toThrow(/two different bodies/);
    expect(() => w.pointLink(ground, wall, pivot)).toThrow(/at least one must be dynamic/);
    expect(() => w.pointLink(a, ground, { x: Number.NaN, y: 0, z: 0 })).toThrow(/worldPivot.x must be a finite number/);
    expect(() => hingeLink(w, a, ground, pivot, { x: 0, y: 0, z: 0 })).toThrow(/axis must be a non-zero vector/);
    expect(() => hingeLink(w, a, ground, pivot, { x: 0, y: 1, z: 0 }, { minRadians: 1, maxRadians: 2 })).toThrow(/limits must satisfy/);
    expect(() => distanceLink(w, a, ground, pivot, pivot, { minDistance: 2, maxDistance: 1 })).toThrow(/minDistance <= maxDistance/);
    expect(() => sliderLink(w, a, ground, pivot, { x: 1, y: 0, z: 0 }, { minMetres: 1, maxMetres: 2 })).toThrow(/min <= 0 <= max/);
    const other = await makeWorld();
    const stranger = other.addSphere(0.2, { x: 0, y: 0, z: 0 });
    expect(() => w.pointLink(a, stranger, pivot)).toThrow(/live bodies of this world/);
    expect(() => w.removeConstraint(other.pointLink(stranger, other.addSphere(0.2, { x: 1, y: 0, z: 0 }), pivot))).toThrow(/not a constraint of this world/);
    other.destroy();
    expect(w.constraintCount).toBe(0);
    const c = w.pointLink(a, ground, pivot);
    w.removeConstraint(c);
    expect(w.constraintCount).toBe(0);
    expect(() => w.removeConstraint(c)).toThrow(/not a constraint of this world/);
    run(w, 10);
    w.destroy();
  });
});
