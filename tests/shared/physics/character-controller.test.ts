// Tests of the character controller: stairs, walls, jumping, ground state, its hittable inner body (rays,
// sensors, pushing), its mask, save/restore, teardown and option checks.
import { describe, expect, it } from 'vitest';
import { CharacterController, CollisionLayer, type PhysicsWorld } from '../../../shared/physics/index.ts';
import { addGround, makeWorld } from '../../helpers/physics.ts';

const DT = 1 / 60;

/** One game tick: physics first, then the character sweeps against the updated world (seed §25.13). */
function tick(w: PhysicsWorld, ch: CharacterController, vx = 0, vz = 0): void {
  w.stepFixed();
  ch.velocity.x = vx;
  ch.velocity.z = vz;
  ch.move(DT);
}

function ticks(w: PhysicsWorld, ch: CharacterController, n: number, vx = 0, vz = 0): void {
  for (let i = 0; i < n; i++) tick(w, ch, vx, vz);
}

describe('character-controller', () => {
  it('walks up a flight of 0.25 m stairs', async () => {
    const w = await makeWorld();
    addGround(w);
    // Six steps, 0.25 m high and 0.6 m deep, starting at x = 2; the landing on top is at y = 1.5.
    for (let i = 0; i < 6; i++) {
      const top = (i + 1) * 0.25;
      w.addBox({ x: 0.3 + (5 - i) * 0.3, y: top / 2, z: 2 }, { x: 2 + i * 0.6 + 0.3 + (5 - i) * 0.3, y: top / 2, z: 0 }, null, { motion: 'static' });
    }
    w.addBox({ x: 2.5, y: 0.75, z: 2 }, { x: 7.5, y: 0.75, z: 0 }, null, { motion: 'static' }); // the landing, x 5..10
    const ch = new CharacterController(w, { position: { x: 0, y: 0, z: 0 } });
    ticks(w, ch, 240, 2);
    expect(ch.position.x).toBeGreaterThan(6.2);
    expect(ch.position.y).toBeCloseTo(1.5, 2);
    expect(ch.groundState).toBe('ground');
    w.destroy();
  });

  it('keeps each character\'s own stair height and size while the world\'s characters share Jolt objects', async () => {
    const w = await makeWorld();
    addGround(w);
    w.addBox({ x: 2, y: 0.125, z: 4 }, { x: 4, y: 0.125, z: 0 }, null, { motion: 'static' }); // a 0.25 m step from x = 2
    const climber = new CharacterController(w, { position: { x: 0, y: 0, z: -2 } });
    const flat = new CharacterController(w, { position: { x: 0, y: 0, z: 0 }, stepUpHeight: 0 });
    const small = new CharacterController(w, { position: { x: 0, y: 0, z: 2 }, radius: 0.2, halfHeight: 0.3 });
    for (let i = 0; i < 120; i++) {
      w.stepFixed();
      for (const ch of [climber, flat, small]) {
        ch.velocity.x = 2;
        ch.move(DT);
      }
    }
    expect(climber.position.y).toBeCloseTo(0.25, 2);
    expect(climber.position.x).toBeGreaterThan(3);
    expect(flat.position.y).toBeLessThan(0.05);
    expect(flat.position.x).toBeLessThan(2);
    expect(small.position.y).toBeCloseTo(0.25, 2);
    const top = w.rayCast({ x: small.position.x, y: 5, z: small.position.z }, { x: 0, y: -10, z: 0 })!;
    expect(top.bodyId).toBe(small.body!.id);
    expect(top.point.y).toBeCloseTo(0.25 + 2 * (0.3 + 0.2), 1); // 1.25 m (+ skin), not a default 1.9 m capsule
    w.destroy();
  });

  it('cannot climb a 1 m wall and stops in front of it', async () => {
    const w = await makeWorld();
    addGround(w);
    w.addBox({ x: 0.5, y: 0.5, z: 3 }, { x: 3, y: 0.5, z: 0 }, null, { motion: 'static' }); // near face at x = 2.5
    const ch = new CharacterController(w, { position: { x: 0, y: 0, z: 0 }, radius: 0.35 });
    ticks(w, ch, 180, 3);
    expect(ch.position.y).toBeCloseTo(0, 2);
    expect(ch.position.x).toBeLessThan(2.5 - 0.35 + 0.01);
    expect(ch.position.x).toBeGreaterThan(2.5 - 0.35 - 0.05);
    expect(ch.groundState).toBe('ground');
    w.destroy();
  });

  it('slides along a wall it walks into at an angle', async () => {
    const w = await makeWorld();
    addGround(w);
    w.addBox({ x: 0.5, y: 2, z: 10 }, { x: 3, y: 2, z: 0 }, null, { motion: 'static' });
    const ch = new CharacterController(w, { position: { x: 0, y: 0, z: 0 } });
    ticks(w, ch, 120, 3, 1);
    expect(ch.position.x).toBeLessThan(2.5 - 0.35 + 0.01);
    expect(ch.position.z).toBeGreaterThan(1.5); // kept moving along the wall
    w.destroy();
  });

  it('jumps only when grounded and reports ground, air and ground again', async () => {
    const w = await makeWorld();
    addGround(w);
    const ch = new CharacterController(w, { position: { x: 0, y: 0.5, z: 0 } });
    ticks(w, ch, 30);
    expect(ch.groundState).toBe('ground');
    expect(ch.isGrounded).toBe(true);
    expect(ch.groundNormal.y).toBeCloseTo(1, 3);
    expect(ch.jump(5)).toBe(true);
    ticks(w, ch, 10);
    expect(ch.groundState).toBe('air');
    expect(ch.isGrounded).toBe(false);
    expect(ch.position.y).toBeGreaterThan(0.5);
    expect(ch.jump(5)).toBe(false); // no double jump
    let peak = 0;
    for (let i = 0; i < 90; i++) {
      tick(w, ch);
      peak = Math.max(peak, ch.position.y);
    }
    expect(peak).toBeGreaterThan(1.1); // v²/2g = 1.27 m
    expect(peak).toBeLessThan(1.4);
    expect(ch.groundState).toBe('ground');
    expect(ch.position.y).toBeCloseTo(0, 2);
    expect(ch.jump(5)).toBe(true);
    expect(() => ch.jump(0)).toThrow(/speed must be a finite number > 0/);
    w.destroy();
  });

  it('reports steep ground on a slope steeper than maxSlopeDegrees and slides down it', async () => {
    const w = await makeWorld();
    addGround(w);
    // A 60° ramp (rotated about z): steeper than the default 45° limit.
    const s = Math.sin(Math.PI / 6);
    const c = Math.cos(Math.PI / 6);
    w.addBox({ x: 3, y: 0.2, z: 3 }, { x: 0, y: 2.5, z: 0 }, { x: 0, y: 0, z: s, w: c }, { motion: 'static' });
    const ch = new CharacterController(w, { position: { x: -0.5, y: 4, z: 0 } });
    let sawSteep = false;
    const startY = ch.position.y;
    for (let i = 0; i < 40; i++) {
      tick(w, ch);
      if (ch.groundState === 'steep') sawSteep = true;
    }
    expect(sawSteep).toBe(true);
    expect(ch.position.y).toBeLessThan(startY - 0.5);
    w.destroy();
  });

  it('is hit by rays and seen by sensors through its inner body', async () => {
    const w = await makeWorld();
    addGround(w);
    const zone = w.addBox({ x: 1, y: 1, z: 1 }, { x: 3, y: 1, z: 0 }, null, { motion: 'static', isSensor: true });
    const ch = new CharacterController(w, { position: { x: 0, y: 0, z: 0 }, name: 'hero' });
    tick(w, ch);
    expect(ch.body).toBeDefined();
    expect(ch.body!.role).toBe('character');
    expect(ch.body!.layer).toBe(CollisionLayer.Player);
    const hit = w.rayCast({ x: -5, y: 1, z: 0 }, { x: 10, y: 0, z: 0 })!;
    expect(hit.bodyId).toBe(ch.body!.id);
    expect(hit.point.x).toBeCloseTo(-0.35, 2);
    expect(w.rayCast({ x: -5, y: 1, z: 0 }, { x: 10, y: 0, z: 0 }, true)).toBeNull(); // staticOnly looks past it
    const events: string[] = [];
    for (let i = 0; i < 150; i++) {
      w.stepFixed().forEach((e) => events.push(`${e.kind} ${e.sensorId} ${e.otherId}`));
      ch.velocity.x = 3;
      ch.move(DT);
    }
    expect(events).toEqual([`enter ${zone.id} ${ch.body!.id}`, `exit ${zone.id} ${ch.body!.id}`]);
    w.destroy();
  });

  it('pushes a light crate out of its way', async () => {
    const w = await makeWorld();
    addGround(w);
    const crate = w.addBox({ x: 0.3, y: 0.3, z: 0.3 }, { x: 2, y: 0.3, z: 0 }, null, { massKg: 5, friction: 0.2 });
    const ch = new CharacterController(w, { position: { x: 0, y: 0, z: 0 } });
    ticks(w, ch, 120, 2);
    expect(crate.position().x).toBeGreaterThan(2.5);
    expect(ch.position.x).toBeGreaterThan(1.5);
    w.destroy();
  });

  it('walks through bodies its mask leaves out', async () => {
    const w = await makeWorld();
    addGround(w);
    w.addBox({ x: 0.5, y: 1, z: 2 }, { x: 2, y: 1, z: 0 }, null, { motion: 'static', layer: CollisionLayer.Prop });
    const ghost = new CharacterController(w, { position: { x: 0, y: 0, z: 0 }, mask: CollisionLayer.World });
    ticks(w, ghost, 120, 3);
    expect(ghost.position.x).toBeGreaterThan(5);
    expect(ghost.position.y).toBeCloseTo(0, 2); // still stands on the World ground
    w.destroy();
  });

  it('restores a saved state and replays the same path bit for bit', async () => {
    const w = await makeWorld();
    addGround(w);
    const ch = new CharacterController(w, { position: { x: 0, y: 0, z: 0 } });
    ticks(w, ch, 20, 2);
    ch.jump(4);
    const saved = ch.saveState();
    expect(saved.length).toBeGreaterThan(32);
    const path = (): number[] => {
      const out: number[] = [];
      for (let i = 0; i < 40; i++) {
        ch.velocity.x = 2;
        ch.move(DT); // no world step: the character alone is rewound
        const p = ch.position;
        out.push(p.x, p.y, p.z, ch.velocity.y);
      }
      return out;
    };
    const first = path();
    ch.restoreState(saved);
    expect(ch.jumpPending).toBe(true);
    expect(path()).toEqual(first);
    expect(() => ch.restoreState(saved.subarray(0, 40))).toThrow(/truncated or corrupt/);
    expect(() => ch.restoreState(new Uint8Array(3))).toThrow(/buffer too short/);
    w.destroy();
  });

  it('removes its inner body from the world when destroyed', async () => {
    const w = await makeWorld();
    const before = w.system.GetNumBodies();
    const ch = new CharacterController(w, { position: { x: 0, y: 0, z: 0 } });
    const innerId = ch.body!.id;
    expect(w.bodyCount).toBe(1);
    expect(w.system.GetNumBodies()).toBe(before + 1);
    expect(() => w.removeBody(innerId)).toThrow(/belongs to a CharacterController/);
    ch.destroy();
    expect(w.bodyCount).toBe(0);
    expect(w.system.GetNumBodies()).toBe(before);
    expect(ch.body!.removed).toBe(true);
    expect(() => ch.move(DT)).toThrow(/CharacterController was destroyed/);
    expect(() => ch.position).toThrow(/destroyed/);
    ch.destroy(); // idempotent
    w.destroy();
  });

  it('rejects bad options with a clear Error and adds nothing', async () => {
    const w = await makeWorld();
    const at = { x: 0, y: 0, z: 0 };
    expect(() => new CharacterController(w, { position: at, radius: 0 })).toThrow(/radius must be a finite number > 0/);
    expect(() => new CharacterController(w, { position: at, halfHeight: Number.NaN })).toThrow(/halfHeight/);
    expect(() => new CharacterController(w, { position: { x: 0, y: Number.POSITIVE_INFINITY, z: 0 } })).toThrow(/position.y must be a finite number/);
    expect(() => new CharacterController(w, { position: at, maxSlopeDegrees: 95 })).toThrow(/maxSlopeDegrees/);
    expect(() => new CharacterController(w, { position: at, layer: 0 })).toThrow(/layer must be/);
    expect(() => new CharacterController(w, { position: at, stepUpHeight: -1 })).toThrow(/stepUpHeight/);
    expect(w.bodyCount).toBe(0);
    const ch = new CharacterController(w, { position: at });
    ch.velocity.x = Number.NaN;
    expect(() => ch.move(DT)).toThrow(/velocity must be finite/);
    expect(() => ch.move(0)).toThrow(/dtSeconds must be > 0/);
    w.destroy();
  });
});
