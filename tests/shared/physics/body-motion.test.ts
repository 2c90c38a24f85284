// Tests of motion control: velocities, impulses, kinematic moves and teleports do what a game expects, wake
// sleeping bodies, and refuse bodies that cannot move that way with a clear Error.
import { describe, expect, it } from 'vitest';
import { addGround, makeWorld, run, settle } from '../../helpers/physics.ts';

describe('body-motion', () => {
  it('sets linear and angular velocity, waking a sleeping body', async () => {
    const w = await makeWorld();
    addGround(w, { friction: 0 });
    const puck = w.addBox({ x: 0.3, y: 0.1, z: 0.3 }, { x: 0, y: 0.1, z: 0 }, null, { friction: 0, linearDamping: 0, angularDamping: 0 });
    settle(w, [puck]);
    expect(puck.isActive()).toBe(false);
    w.setLinearVelocity(puck, { x: 2, y: 0, z: 0 });
    w.setAngularVelocity(puck.id, { x: 0, y: 3, z: 0 });
    expect(puck.isActive()).toBe(true);
    run(w, 60);
    expect(puck.position().x).toBeCloseTo(2, 1);
    expect(puck.angularVelocity().y).toBeCloseTo(3, 2);
    w.destroy();
  });

  it('applies an impulse as a change of momentum, with spin when applied off-centre', async () => {
    const w = await makeWorld({ gravity: { x: 0, y: 0, z: 0 } });
    const a = w.addSphere(0.5, { x: 0, y: 0, z: 0 }, { massKg: 4, linearDamping: 0 });
    const b = w.addBox({ x: 0.5, y: 0.5, z: 0.5 }, { x: 5, y: 0, z: 0 }, null, { massKg: 2, linearDamping: 0, angularDamping: 0 });
    w.addImpulse(a, { x: 8, y: 0, z: 0 });
    w.addImpulse(b, { x: 0, y: 0, z: 2 }, { x: 5.5, y: 0, z: 0 }); // at the +x face: spins about -y
    w.stepFixed();
    expect(a.linearVelocity().x).toBeCloseTo(2, 4); // 8 N·s / 4 kg
    expect(b.linearVelocity().z).toBeCloseTo(1, 4);
    expect(b.angularVelocity().y).toBeLessThan(-0.5);
    w.destroy();
  });

  it('moves a kinematic body to its target in one tick, pushing what is in the way', async () => {
    const w = await makeWorld();
    addGround(w);
    const pusher = w.addBox({ x: 0.2, y: 0.5, z: 1 }, { x: -1, y: 0.5, z: 0 }, null, { motion: 'kinematic' });
    const crate = w.addBox({ x: 0.25, y: 0.25, z: 0.25 }, { x: 0, y: 0.25, z: 0 }, null, { massKg: 1 });
    w.moveKinematic(pusher, { x: -0.9, y: 0.5, z: 0 }, null);
    w.stepFixed();
    expect(pusher.position().x).toBeCloseTo(-0.9, 4);
    expect(pusher.linearVelocity().x).toBeCloseTo(6, 3); // 0.1 m in 1/60 s
    for (let t = 0; t < 60; t++) {
      w.moveKinematic(pusher, { x: pusher.position().x + 0.05, y: 0.5, z: 0 }, null);
      w.stepFixed();
    }
    expect(pusher.position().x).toBeCloseTo(2.1, 3);
    expect(crate.position().x).toBeGreaterThan(2.1 + 0.2); // shoved ahead of the pusher
    const quarter = { x: 0, y: Math.SQRT1_2, z: 0, w: Math.SQRT1_2 };
    w.moveKinematic(pusher, pusher.position(), quarter, 0.5); // a slower turn: over half a second
    run(w, 30);
    expect(Math.abs(pusher.rotation().y)).toBeCloseTo(Math.SQRT1_2, 3);
    w.destroy();
  });

  it('teleports a body, keeping its velocity, and moves a static body for rays', async () => {
    const w = await makeWorld({ gravity: { x: 0, y: 0, z: 0 } });
    const ball = w.addSphere(0.2, { x: 0, y: 0, z: 0 }, { linearVelocity: { x: 1, y: 0, z: 0 }, linearDamping: 0 });
    w.setPosition(ball, { x: 10, y: 5, z: 0 });
    expect(ball.position()).toEqual({ x: 10, y: 5, z: 0 });
    run(w, 60);
    expect(ball.position().x).toBeCloseTo(11, 2);
    const wall = w.addBox({ x: 1, y: 1, z: 0.1 }, { x: 0, y: 0, z: 5 }, null, { motion: 'static' });
    w.setPosition(wall, { x: 20, y: 0, z: 5 });
    expect(w.rayCast({ x: 0, y: 0, z: 0 }, { x: 0, y: 0, z: 10 })).toBeNull();
    expect(w.rayCast({ x: 20, y: 0, z: 0 }, { x: 0, y: 0, z: 10 })?.bodyId).toBe(wall.id);
    w.destroy();
  });

  it('refuses motion a body cannot take, and bad numbers, with a clear Error', async () => {
    const w = await makeWorld();
    const ground = addGround(w);
    const lift = w.addBox({ x: 1, y: 0.1, z: 1 }, { x: 0, y: 1, z: 0 }, null, { motion: 'kinematic' });
    const zone = w.addBox({ x: 1, y: 1, z: 1 }, { x: 5, y: 1, z: 0 }, null, { motion: 'static', isSensor: true });
    const ball = w.addSphere(0.2, { x: 0, y: 3, z: 0 });
    const v = { x: 1, y: 0, z: 0 };
    expect(() => w.setLinearVelocity(ground, v)).toThrow(/body 1 is static; static bodies never move/);
    expect(() => w.setAngularVelocity(zone, v)).toThrow(/is static/);
    expect(() => w.addImpulse(lift, v)).toThrow(/is kinematic; only dynamic bodies take impulses/);
    expect(() => w.addImpulse(ground, v)).toThrow(/is static; only dynamic bodies/);
    expect(() => w.moveKinematic(ball, v, null)).toThrow(/is dynamic, not kinematic/);
    expect(() => w.moveKinematic(lift, v, null, 0)).toThrow(/dtSeconds must be a finite number > 0/);
    expect(() => w.moveKinematic(lift, v, { x: 0, y: 0, z: 0, w: 0 })).toThrow(/rotation must be a unit quaternion/);
    expect(() => w.setLinearVelocity(ball, { x: Number.NaN, y: 0, z: 0 })).toThrow(/velocity.x must be a finite number/);
    expect(() => w.addImpulse(ball, v, { x: 0, y: Number.POSITIVE_INFINITY, z: 0 })).toThrow(/worldPoint.y/);
    expect(() => w.setPosition(ball, { x: 0, y: 0, z: Number.NaN })).toThrow(/position.z/);
    expect(() => w.setLinearVelocity(999, v)).toThrow(/setLinearVelocity: no body 999 in this world/);
    expect(ball.linearVelocity()).toEqual({ x: 0, y: 0, z: 0 }); // nothing half-applied
    run(w, 5);
    w.destroy();
  });
});
