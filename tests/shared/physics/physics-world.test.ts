// Tests of PhysicsWorld: every factory makes a body that comes to rest where a user expects, static-only shapes
// refuse dynamics, ids are stable across worlds, stepping clamps long frames, and removal/clear/destroy behave.
import { describe, expect, it } from 'vitest';
import { BODY_STATE_STRIDE, CharacterController, CollisionLayer, hingeLink, PhysicsWorld } from '../../../shared/physics/index.ts';
import { addGround, distance, makeWorld, rotate, run, settle } from '../../helpers/physics.ts';

describe('physics-world', () => {
  it('rests a dropped box on the ground at its half height, within 1 cm', async () => {
    const w = await makeWorld();
    addGround(w);
    const box = w.addBox({ x: 0.5, y: 0.3, z: 0.4 }, { x: 0, y: 2, z: 0 });
    settle(w, [box]);
    expect(box.isActive()).toBe(false);
    expect(box.position().y).toBeCloseTo(0.3, 2);
    expect(Math.abs(box.position().y - 0.3)).toBeLessThan(0.01);
    w.destroy();
  });

  it('bounces a sphere with restitution 0.8 higher than one with restitution 0', async () => {
    const w = await makeWorld();
    addGround(w, { restitution: 0 });
    const bouncy = w.addSphere(0.25, { x: -2, y: 2.25, z: 0 }, { restitution: 0.8 });
    const dead = w.addSphere(0.25, { x: 2, y: 2.25, z: 0 }, { restitution: 0 });
    const peak = { bouncy: 0, dead: 0 };
    let landed = false;
    for (let t = 0; t < 180; t++) {
      w.stepFixed();
      if (bouncy.position().y < 0.3) landed = true;
      if (landed) {
        peak.bouncy = Math.max(peak.bouncy, bouncy.position().y - 0.25);
        peak.dead = Math.max(peak.dead, dead.position().y - 0.25);
      }
    }
    // Dropped from 2 m: e = 0.8 rebounds to about e² · 2 m = 1.28 m; e = 0 stays down.
    expect(peak.bouncy).toBeGreaterThan(0.9);
    expect(peak.dead).toBeLessThan(0.05);
    w.destroy();
  });

  it('stands an upright capsule on its end with its centre at halfHeight + radius', async () => {
    const w = await makeWorld();
    addGround(w);
    const capsule = w.addCapsule(0.6, 0.3, { x: 0, y: 1.5, z: 0 });
    settle(w, [capsule]);
    expect(Math.abs(capsule.position().y - 0.9)).toBeLessThan(0.01);
    const axis = rotate(capsule.rotation(), { x: 0, y: 1, z: 0 });
    expect(axis.y).toBeGreaterThan(0.999);
    w.destroy();
  });

  it('rests a convex hull from a point cloud on one of its flat faces', async () => {
    const w = await makeWorld();
    addGround(w);
    // A square-based pyramid, dropped tilted: whichever face it lands on, three or more corners touch the ground.
    const corners = [
      { x: -0.5, y: 0, z: -0.5 },
      { x: 0.5, y: 0, z: -0.5 },
      { x: 0.5, y: 0, z: 0.5 },
      { x: -0.5, y: 0, z: 0.5 },
      { x: 0, y: 0.8, z: 0 },
    ];
    const tilt = { x: 0.2588, y: 0, z: 0, w: 0.9659 }; // 30° about x
    const hull = w.addConvexHull(corners, { x: 0, y: 2, z: 0 }, tilt);
    settle(w, [hull]);
    expect(hull.isActive()).toBe(false);
    const p = hull.position();
    const q = hull.rotation();
    const heights = corners.map((c) => rotate(q, c).y + p.y).sort((a, b) => a - b);
    expect(heights[0]).toBeGreaterThan(-0.01);
    expect(heights[2]).toBeLessThan(0.01); // the three lowest corners lie on the ground: a face, not an edge
    w.destroy();
  });

  it('stops a sphere on a static mesh collider at the surface height', async () => {
    const w = await makeWorld();
    // A 10 m square at y = 1.5 made of two triangles (wound so their normals face up).
    const positions = [-5, 1.5, -5, 5, 1.5, -5, 5, 1.5, 5, -5, 1.5, 5];
    const mesh = w.addMeshCollider(positions, [0, 2, 1, 0, 3, 2], { x: 0, y: 0, z: 0 });
    expect(mesh.motion).toBe('static');
    const ball = w.addSphere(0.4, { x: 1, y: 4, z: -1 });
    settle(w, [ball]);
    expect(Math.abs(ball.position().y - 1.9)).toBeLessThan(0.01);
    w.destroy();
  });

  it('stops a sphere on a height field at the sampled height', async () => {
    const w = await makeWorld();
    // A 9×9 bowl, 1 m cells, whose lowest sample (2.35 m) sits at the centre.
    const n = 9;
    const heights: number[] = [];
    for (let z = 0; z < n; z++) for (let x = 0; x < n; x++) heights.push(2.35 + 0.3 * ((x - 4) * (x - 4) + (z - 4) * (z - 4)));
    w.addHeightField(heights, n, 1, { x: -4, z: -4 });
    const ball = w.addSphere(0.2, { x: 0.3, y: 6, z: -0.2 });
    settle(w, [ball], 900);
    const p = ball.position();
    expect(Math.abs(p.x)).toBeLessThan(0.05);
    expect(Math.abs(p.z)).toBeLessThan(0.05);
    // Resting in the bowl's lowest cell corner: touching the four surrounding slopes, never sunk below the sample.
    expect(p.y - 0.2).toBeGreaterThan(2.35 - 0.01);
    expect(p.y - 0.2).toBeLessThan(2.35 + 0.06);
    expect(w.rayDownY(0, 10, 0, 20, true)).toBeCloseTo(2.35, 3);
    w.destroy();
  });

  it('stands a cylinder on its flat end at its half height', async () => {
    const w = await makeWorld();
    addGround(w);
    const cyl = w.addCylinder(0.5, 0.3, { x: 0, y: 1, z: 0 });
    settle(w, [cyl]);
    expect(Math.abs(cyl.position().y - 0.5)).toBeLessThan(0.01);
    expect(rotate(cyl.rotation(), { x: 0, y: 1, z: 0 }).y).toBeGreaterThan(0.999);
    w.destroy();
  });

  it('rests a compound table on its four legs', async () => {
    const w = await makeWorld();
    addGround(w);
    const leg = { kind: 'box' as const, halfExtents: { x: 0.05, y: 0.4, z: 0.05 } };
    const table = w.addCompound(
      [
        { shape: { kind: 'box', halfExtents: { x: 0.8, y: 0.05, z: 0.5 } }, position: { x: 0, y: 0.45, z: 0 } },
        { shape: leg, position: { x: -0.7, y: 0, z: -0.4 } },
        { shape: leg, position: { x: 0.7, y: 0, z: -0.4 } },
        { shape: leg, position: { x: -0.7, y: 0, z: 0.4 } },
        { shape: leg, position: { x: 0.7, y: 0, z: 0.4 } },
      ],
      { x: 0, y: 1.5, z: 0 },
    );
    settle(w, [table]);
    // The body origin is the compound's origin: legs reach 0.4 m below it.
    expect(Math.abs(table.position().y - 0.4)).toBeLessThan(0.01);
    expect(rotate(table.rotation(), { x: 0, y: 1, z: 0 }).y).toBeGreaterThan(0.999);
    expect(w.rayDownY(0, 3, 0, 5)).toBeCloseTo(0.9, 2); // a ray from above hits the table top
    w.destroy();
  });

  it('refuses a dynamic mesh or height field and a kinematic height field, creating nothing', async () => {
    const w = await makeWorld();
    const tri = { positions: [0, 0, 0, 1, 0, 0, 0, 0, 1], indices: [0, 2, 1] };
    expect(() => w.addMeshCollider(tri.positions, tri.indices, { x: 0, y: 0, z: 0 }, null, { motion: 'dynamic' })).toThrow(/can only be static or kinematic/);
    expect(() => w.addHeightField([0, 0, 0, 0], 2, 1, { x: 0, z: 0 }, { motion: 'dynamic' })).toThrow(/can only be static or kinematic/);
    expect(() => w.addHeightField([0, 0, 0, 0], 2, 1, { x: 0, z: 0 }, { motion: 'kinematic' })).toThrow(/can only be static/);
    expect(w.addMeshCollider(tri.positions, tri.indices, { x: 0, y: 0, z: 0 }, null, { motion: 'kinematic' }).motion).toBe('kinematic');
    expect(w.bodyCount).toBe(1);
    w.destroy();
  });

  it('gives the same ids and bit-identical states to two worlds built in the same order', async () => {
    const build = async (): Promise<PhysicsWorld> => {
      const w = await makeWorld();
      addGround(w);
      for (let i = 0; i < 12; i++) {
        const pos = { x: (i % 4) - 1.5, y: 1 + i * 0.6, z: (i % 3) * 0.3 };
        if (i % 3 === 0) w.addBox({ x: 0.2, y: 0.2, z: 0.2 }, pos);
        else if (i % 3 === 1) w.addSphere(0.25, pos);
        else w.addCapsule(0.2, 0.15, pos, { x: 0, y: 0, z: 0.7071, w: 0.7071 });
      }
      run(w, 120);
      return w;
    };
    const a = await build();
    const b = await build();
    expect(b.bodyIds()).toEqual(a.bodyIds());
    const sa = a.readBodyStates();
    const copy = Array.from(sa.states);
    const sb = b.readBodyStates();
    expect(Array.from(sb.ids)).toEqual(Array.from(sa.ids));
    expect(Array.from(sb.states)).toEqual(copy);
    expect(copy.length).toBe(13 * BODY_STATE_STRIDE);
    a.destroy();
    b.destroy();
  });

  it('throws a clear Error at maxBodies and accepts a body again after a removal', async () => {
    const w = await makeWorld({ maxBodies: 8 });
    const bodies = Array.from({ length: 8 }, (_, i) => w.addSphere(0.1, { x: i, y: 0, z: 0 }));
    expect(() => w.addBox({ x: 1, y: 1, z: 1 }, { x: 0, y: 5, z: 0 })).toThrow(/world is full \(8 bodies/);
    expect(() => new CharacterController(w, { position: { x: 0, y: 0, z: 0 } })).toThrow(/world is full/);
    expect(w.bodyCount).toBe(8);
    w.removeBody(bodies[3]);
    const again = w.addSphere(0.1, { x: 3, y: 0, z: 0 });
    expect(again.id).toBe(9);
    run(w, 2);
    w.destroy();
  });

  it('clamps a long frame to 1/30 s and splits it into two collision steps', async () => {
    const w = await makeWorld();
    const ball = w.addSphere(0.1, { x: 0, y: 100, z: 0 }, { linearDamping: 0 });
    w.step(2.0); // a tab woken after two seconds advances only 1/30 s
    expect(ball.linearVelocity().y).toBeCloseTo(-9.81 / 30, 4);
    expect(() => w.step(0)).toThrow(/dtSeconds must be a finite number > 0/);
    expect(() => w.step(Number.NaN)).toThrow(/dtSeconds/);
    w.destroy();
  });

  it('applies the gravity option and setGravity', async () => {
    const w = await makeWorld({ gravity: { x: 0, y: -1, z: 0 } });
    const ball = w.addSphere(0.1, { x: 0, y: 10, z: 0 }, { linearDamping: 0 });
    run(w, 60);
    expect(ball.linearVelocity().y).toBeCloseTo(-1, 2);
    w.setGravity(2, 0, 0);
    run(w, 60);
    expect(ball.linearVelocity().x).toBeCloseTo(2, 2);
    expect(() => w.setGravity(0, Number.POSITIVE_INFINITY, 0)).toThrow(/gravity.y must be a finite number/);
    await expect(PhysicsWorld.create({ gravity: { x: 0, y: Number.NaN, z: 0 } })).rejects.toThrow(/gravity.y/);
    w.destroy();
  });

  it('removes a body with its constraints; its handle throws and its id is never handed out again', async () => {
    const w = await makeWorld();
    const a = w.addSphere(0.2, { x: 0, y: 2, z: 0 });
    const b = w.addSphere(0.2, { x: 1, y: 2, z: 0 });
    w.pointLink(a, b, { x: 0.5, y: 2, z: 0 });
    expect(w.constraintCount).toBe(1);
    w.removeBody(a);
    expect(w.constraintCount).toBe(0);
    expect(a.removed).toBe(true);
    expect(() => a.position()).toThrow(/body 1 was removed/);
    expect(() => w.removeBody(a)).toThrow(/no body 1 in this world/);
    expect(() => w.setLinearVelocity(a, { x: 1, y: 0, z: 0 })).toThrow(/no body 1/);
    expect(w.getBody(1)).toBeUndefined();
    expect(w.addSphere(0.2, { x: 0, y: 2, z: 0 }).id).toBe(3);
    run(w, 10);
    w.destroy();
  });

  it('clear() removes every body and constraint but leaves characters to their owners', async () => {
    const w = await makeWorld();
    addGround(w);
    const a = w.addBox({ x: 0.2, y: 0.2, z: 0.2 }, { x: 0, y: 1, z: 0 });
    const b = w.addBox({ x: 0.2, y: 0.2, z: 0.2 }, { x: 1, y: 1, z: 0 });
    hingeLink(w, a, b, { x: 0.5, y: 1, z: 0 }, { x: 0, y: 0, z: 1 });
    const ch = new CharacterController(w, { position: { x: 5, y: 0, z: 0 } });
    w.clear();
    expect(w.bodyIds()).toEqual([ch.body!.id]);
    expect(w.constraintCount).toBe(0);
    run(w, 5);
    ch.move(1 / 60);
    ch.destroy();
    expect(w.bodyCount).toBe(0);
    w.destroy();
  });

  it('destroy() frees the world and makes every further call throw a clear Error', async () => {
    const w = await makeWorld();
    const ball = w.addSphere(0.2, { x: 0, y: 1, z: 0 });
    const ch = new CharacterController(w, { position: { x: 3, y: 0, z: 0 } });
    w.destroy();
    expect(w.isDestroyed).toBe(true);
    expect(ch.isDestroyed).toBe(true);
    expect(ball.removed).toBe(true);
    expect(() => w.addSphere(0.2, { x: 0, y: 1, z: 0 })).toThrow(/PhysicsWorld was destroyed/);
    expect(() => w.stepFixed()).toThrow(/PhysicsWorld was destroyed/);
    expect(() => w.rayCast({ x: 0, y: 1, z: 0 }, { x: 0, y: -1, z: 0 })).toThrow(/PhysicsWorld was destroyed/);
    expect(() => w.readBodyStates()).toThrow(/PhysicsWorld was destroyed/);
    expect(() => w.setLinearVelocity(1, { x: 0, y: 0, z: 0 })).toThrow(/PhysicsWorld was destroyed/);
    w.destroy(); // idempotent
  });

  it('keeps simulating, building shapes and casting rays after another world is destroyed', async () => {
    // Destroying a JoltInterface clears Jolt's global type factory and default material while other worlds live on.
    const a = await makeWorld();
    const b = await makeWorld();
    a.destroy();
    addGround(b);
    b.addMeshCollider([-5, 1, -5, 5, 1, -5, 5, 1, 5, -5, 1, 5], [0, 2, 1, 0, 3, 2], { x: 20, y: 0, z: 0 });
    b.addHeightField([0.5, 0.5, 0.5, 0.5, 0.5, 0.5, 0.5, 0.5, 0.5], 3, 1, { x: -20, z: 0 });
    const hull = b.addConvexHull([0, 0, 0, 1, 0, 0, 0, 1, 0, 0, 0, 1], { x: 0, y: 2, z: 0 });
    const onMesh = b.addSphere(0.3, { x: 20, y: 3, z: 0 });
    const onField = b.addSphere(0.3, { x: -19, y: 3, z: 1 });
    const ch = new CharacterController(b, { position: { x: 5, y: 0, z: 5 } });
    for (let t = 0; t < 120; t++) {
      b.stepFixed();
      ch.velocity.x = 1;
      ch.move(1 / 60);
    }
    expect(onMesh.position().y).toBeCloseTo(1.3, 2);
    expect(onField.position().y).toBeCloseTo(0.8, 2);
    expect(hull.position().y).toBeCloseTo(0, 2);
    expect(ch.groundState).toBe('ground');
    expect(distance(ch.position, { x: 7, y: 0, z: 5 })).toBeLessThan(0.05);
    expect(b.rayCast({ x: 20, y: 5, z: 0 }, { x: 0, y: -10, z: 0 })?.bodyId).toBe(onMesh.id);
    b.destroy();
    const c = await makeWorld({ maxBodies: 4, maxContactConstraints: 64, maxBodyPairs: 64 });
    expect(c.addSphere(0.1, { x: 0, y: 0, z: 0 }).id).toBe(1);
    c.destroy();
  });

  it('checks layer and mask bits when a body is created', async () => {
    const w = await makeWorld();
    expect(w.addSphere(0.1, { x: 0, y: 0, z: 0 }).layer).toBe(CollisionLayer.Prop);
    expect(w.addSphere(0.1, { x: 0, y: 0, z: 0 }, { motion: 'static' }).layer).toBe(CollisionLayer.World);
    expect(w.addSphere(0.1, { x: 0, y: 0, z: 0 }, { isSensor: true }).layer).toBe(CollisionLayer.Trigger);
    expect(() => w.addSphere(0.1, { x: 0, y: 0, z: 0 }, { layer: 0 })).toThrow(/layer must be a non-zero integer/);
    expect(() => w.addSphere(0.1, { x: 0, y: 0, z: 0 }, { mask: 0x10000 })).toThrow(/mask must be a non-zero integer/);
    expect(() => w.addSphere(0.1, { x: 0, y: 0, z: 0 }, { layer: 1.5 })).toThrow(/layer/);
    expect(w.bodyCount).toBe(3);
    w.destroy();
  });
});
