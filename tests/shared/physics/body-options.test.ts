// Tests of BodyOptions: each tunable changes what a user sees (friction, gravity factor, mass, damping, sleeping,
// initial velocities, the legacy dynamic flag, no-collide groups), and the defaults are the documented ones.
import { describe, expect, it } from 'vitest';
import { addGround, makeWorld, run, settle } from '../../helpers/physics.ts';

describe('body-options', () => {
  it('holds a box on a 20° slope with friction 1 and lets it slide with friction 0', async () => {
    const w = await makeWorld();
    const tilt = { x: 0, y: 0, z: Math.sin(Math.PI / 18), w: Math.cos(Math.PI / 18) }; // 20° about z
    w.addBox({ x: 10, y: 0.5, z: 5 }, { x: 0, y: 0, z: 0 }, tilt, { motion: 'static', friction: 1 });
    const sticky = w.addBox({ x: 0.3, y: 0.3, z: 0.3 }, { x: 0, y: 0.9, z: -2 }, tilt, { friction: 1 });
    const slick = w.addBox({ x: 0.3, y: 0.3, z: 0.3 }, { x: 0, y: 0.9, z: 2 }, tilt, { friction: 0 });
    run(w, 90);
    expect(Math.abs(sticky.position().x)).toBeLessThan(0.1);
    expect(slick.position().x).toBeLessThan(-1); // slid down towards -x
    w.destroy();
  });

  it('scales gravity per body with gravityFactor', async () => {
    const w = await makeWorld();
    const floating = w.addSphere(0.2, { x: 0, y: 5, z: 0 }, { gravityFactor: 0 });
    const light = w.addSphere(0.2, { x: 2, y: 5, z: 0 }, { gravityFactor: 0.5, linearDamping: 0 });
    run(w, 60);
    expect(floating.position().y).toBe(5);
    expect(light.linearVelocity().y).toBeCloseTo(-9.81 / 2, 2);
    w.destroy();
  });

  it('uses massKg for how hard an impulse moves a body', async () => {
    const w = await makeWorld({ gravity: { x: 0, y: 0, z: 0 } });
    const heavy = w.addBox({ x: 0.5, y: 0.5, z: 0.5 }, { x: 0, y: 0, z: 0 }, null, { massKg: 100, linearDamping: 0 });
    const light = w.addBox({ x: 0.5, y: 0.5, z: 0.5 }, { x: 3, y: 0, z: 0 }, null, { massKg: 1, linearDamping: 0 });
    w.addImpulse(heavy, { x: 10, y: 0, z: 0 });
    w.addImpulse(light, { x: 10, y: 0, z: 0 });
    w.stepFixed();
    expect(heavy.linearVelocity().x).toBeCloseTo(0.1, 3);
    expect(light.linearVelocity().x).toBeCloseTo(10, 2);
    w.destroy();
  });

  it('starts bodies with their initial velocities, and damping slows them', async () => {
    const w = await makeWorld({ gravity: { x: 0, y: 0, z: 0 } });
    const free = w.addSphere(0.2, { x: 0, y: 0, z: 0 }, { linearVelocity: { x: 3, y: 0, z: 0 }, angularVelocity: { x: 0, y: 0, z: 2 }, linearDamping: 0, angularDamping: 0 });
    const damped = w.addSphere(0.2, { x: 0, y: 5, z: 0 }, { linearVelocity: { x: 3, y: 0, z: 0 }, linearDamping: 2 });
    run(w, 60);
    expect(free.position().x).toBeCloseTo(3, 2);
    expect(free.angularVelocity().z).toBeCloseTo(2, 4);
    expect(damped.linearVelocity().x).toBeLessThan(1);
    w.destroy();
  });

  it('keeps a body awake with allowSleeping: false', async () => {
    const w = await makeWorld();
    addGround(w);
    const sleepy = w.addBox({ x: 0.2, y: 0.2, z: 0.2 }, { x: 0, y: 0.2, z: 0 });
    const awake = w.addBox({ x: 0.2, y: 0.2, z: 0.2 }, { x: 2, y: 0.2, z: 0 }, null, { allowSleeping: false });
    settle(w, [sleepy]);
    run(w, 120);
    expect(sleepy.isActive()).toBe(false);
    expect(awake.isActive()).toBe(true);
    w.destroy();
  });

  it('bounces with the default restitution of 0.2', async () => {
    const w = await makeWorld();
    addGround(w, { restitution: 0 });
    const ball = w.addSphere(0.2, { x: 0, y: 2.2, z: 0 });
    let landed = false;
    let peak = 0;
    for (let t = 0; t < 120; t++) {
      w.stepFixed();
      if (ball.position().y < 0.25) landed = true;
      else if (landed) peak = Math.max(peak, ball.position().y - 0.2);
    }
    // e = 0.2 from 2 m: about e² · 2 m = 8 cm up again.
    expect(peak).toBeGreaterThan(0.04);
    expect(peak).toBeLessThan(0.12);
    w.destroy();
  });

  it('reads the legacy dynamic flag, with motion winning when both are given', async () => {
    const w = await makeWorld();
    expect(w.addSphere(0.1, { x: 0, y: 0, z: 0 }, { dynamic: false }).motion).toBe('static');
    expect(w.addSphere(0.1, { x: 0, y: 0, z: 0 }, { dynamic: true }).motion).toBe('dynamic');
    expect(w.addSphere(0.1, { x: 0, y: 0, z: 0 }, { dynamic: false, motion: 'kinematic' }).motion).toBe('kinematic');
    expect(w.addSphere(0.1, { x: 0, y: 0, z: 0 }).motion).toBe('dynamic');
    w.destroy();
  });

  it('lets bodies of one no-collide group pass through each other but not through others', async () => {
    const w = await makeWorld({ gravity: { x: 0, y: 0, z: 0 } });
    const shooter = w.addBox({ x: 0.5, y: 0.5, z: 0.5 }, { x: 0, y: 0, z: 0 }, null, { noCollideGroup: 7, massKg: 80 });
    const own = w.addSphere(0.1, { x: -2, y: 0, z: 0 }, { noCollideGroup: 7, linearVelocity: { x: 10, y: 0, z: 0 } });
    const stranger = w.addSphere(0.1, { x: -2, y: 0, z: 3 }, { noCollideGroup: 8, linearVelocity: { x: 10, y: 0, z: 0 } });
    const target = w.addBox({ x: 0.5, y: 0.5, z: 0.5 }, { x: 0, y: 0, z: 3 }, null, { noCollideGroup: 7, massKg: 80 });
    run(w, 30);
    expect(own.position().x).toBeGreaterThan(2); // straight through its own shooter
    expect(stranger.position().x).toBeLessThan(0); // stopped by a body of another group
    expect(shooter.linearVelocity().x).toBe(0);
    expect(target.linearVelocity().x).toBeGreaterThan(0);
    w.destroy();
  });

  it('keeps userData and name on the handle', async () => {
    const w = await makeWorld();
    const tag = { team: 'red' };
    const b = w.addSphere(0.1, { x: 0, y: 0, z: 0 }, { userData: tag, name: 'flag' });
    expect(b.userData).toBe(tag);
    expect(b.name).toBe('flag');
    expect(w.getBody(b.id)).toBe(b);
    w.destroy();
  });
});
