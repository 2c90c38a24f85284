// Tests of ray casts: the nearest hit with its point, body id, normal and fraction; reach; staticOnly; sensors
// ignored; rayDownY heights on terrain; and clear Errors for bad rays.
import { describe, expect, it } from 'vitest';
import { makeWorld, run } from '../../helpers/physics.ts';

describe('queries', () => {
  it('returns the nearest of several bodies on the ray, with point, id, normal and fraction', async () => {
    const w = await makeWorld({ gravity: { x: 0, y: 0, z: 0 } });
    const far = w.addBox({ x: 0.5, y: 0.5, z: 0.5 }, { x: 8, y: 0, z: 0 }, null, { motion: 'static' });
    const near = w.addBox({ x: 0.5, y: 0.5, z: 0.5 }, { x: 4, y: 0, z: 0 });
    const hit = w.rayCast({ x: 0, y: 0.1, z: 0.2 }, { x: 10, y: 0, z: 0 });
    expect(hit).not.toBeNull();
    expect(hit!.bodyId).toBe(near.id);
    expect(hit!.fraction).toBeCloseTo(0.35, 5);
    expect(hit!.point.x).toBeCloseTo(3.5, 5);
    expect(hit!.point.y).toBeCloseTo(0.1, 6);
    expect(hit!.point.z).toBeCloseTo(0.2, 6);
    expect(hit!.normal.x).toBeCloseTo(-1, 5);
    expect(Math.abs(hit!.normal.y) + Math.abs(hit!.normal.z)).toBeLessThan(1e-5);
    w.removeBody(near);
    expect(w.rayCast({ x: 0, y: 0.1, z: 0.2 }, { x: 10, y: 0, z: 0 })!.bodyId).toBe(far.id);
    w.destroy();
  });

  it('reaches exactly |direction| and returns null on a miss', async () => {
    const w = await makeWorld();
    w.addBox({ x: 0.5, y: 0.5, z: 0.5 }, { x: 4, y: 0, z: 0 }, null, { motion: 'static' });
    expect(w.rayCast({ x: 0, y: 0, z: 0 }, { x: 3.4, y: 0, z: 0 })).toBeNull();
    expect(w.rayCast({ x: 0, y: 0, z: 0 }, { x: 3.6, y: 0, z: 0 })?.fraction).toBeCloseTo(3.5 / 3.6, 5);
    expect(w.rayCast({ x: 0, y: 0, z: 0 }, { x: 0, y: 10, z: 0 })).toBeNull();
    w.destroy();
  });

  it('gives the surface normal at the hit on a sphere', async () => {
    const w = await makeWorld({ gravity: { x: 0, y: 0, z: 0 } });
    const ball = w.addSphere(1, { x: 0, y: 0, z: 5 }, { motion: 'static' });
    const hit = w.rayCast({ x: 0.6, y: 0, z: 0 }, { x: 0, y: 0, z: 10 })!;
    expect(hit.bodyId).toBe(ball.id);
    expect(hit.point.z).toBeCloseTo(5 - 0.8, 4);
    expect(hit.normal.x).toBeCloseTo(0.6, 4);
    expect(hit.normal.z).toBeCloseTo(-0.8, 4);
    w.destroy();
  });

  it('ignores dynamic bodies with staticOnly, and sensors always', async () => {
    const w = await makeWorld({ gravity: { x: 0, y: 0, z: 0 } });
    const ground = w.addBox({ x: 5, y: 0.5, z: 5 }, { x: 0, y: -0.5, z: 0 }, null, { motion: 'static' });
    const crate = w.addBox({ x: 0.5, y: 0.5, z: 0.5 }, { x: 0, y: 2, z: 0 });
    w.addBox({ x: 2, y: 0.5, z: 2 }, { x: 0, y: 4, z: 0 }, null, { motion: 'static', isSensor: true });
    expect(w.rayCast({ x: 0, y: 10, z: 0 }, { x: 0, y: -20, z: 0 })!.bodyId).toBe(crate.id);
    const hit = w.rayCast({ x: 0, y: 10, z: 0 }, { x: 0, y: -20, z: 0 }, true)!;
    expect(hit.bodyId).toBe(ground.id);
    expect(hit.point.y).toBeCloseTo(0, 5);
    expect(w.rayDownY(0, 10, 0, 20)).toBeCloseTo(2.5, 5);
    expect(w.rayDownY(0, 10, 0, 20, true)).toBeCloseTo(0, 5);
    w.destroy();
  });

  it('reads terrain heights with rayDownY, and null beyond its reach or off the terrain', async () => {
    const w = await makeWorld();
    const n = 17;
    const heights: number[] = [];
    for (let z = 0; z < n; z++) for (let x = 0; x < n; x++) heights.push(((x * 7 + z * 3) % 5) * 0.4 + x * 0.1);
    w.addHeightField(heights, n, 2, { x: -16, z: -16 });
    let worst = 0;
    for (let z = 1; z < n - 1; z++) {
      for (let x = 1; x < n - 1; x++) {
        const y = w.rayDownY(-16 + x * 2, 20, -16 + z * 2, 40);
        expect(y).not.toBeNull();
        worst = Math.max(worst, Math.abs(y! - heights[z * n + x]));
      }
    }
    expect(worst).toBeLessThan(0.002); // stored to the millimetre
    expect(w.rayDownY(0, 20, 0, 5)).toBeNull(); // the ground is more than 5 m below
    expect(w.rayDownY(17, 20, 0, 40)).toBeNull(); // past the last sample
    w.destroy();
  });

  it('hits mesh colliders and compound parts with their body ids', async () => {
    const w = await makeWorld({ gravity: { x: 0, y: 0, z: 0 } });
    const mesh = w.addMeshCollider([-2, 0, -2, 2, 0, -2, 2, 0, 2, -2, 0, 2], [0, 2, 1, 0, 3, 2], { x: 0, y: 1, z: 0 });
    const compound = w.addCompound([{ shape: { kind: 'sphere', radius: 0.5 }, position: { x: 3, y: 0, z: 0 } }], { x: 0, y: 5, z: 0 });
    expect(w.rayCast({ x: 0.5, y: 3, z: 0.5 }, { x: 0, y: -5, z: 0 })!.bodyId).toBe(mesh.id);
    const hit = w.rayCast({ x: 3, y: 9, z: 0 }, { x: 0, y: -5, z: 0 })!;
    expect(hit.bodyId).toBe(compound.id);
    expect(hit.point.y).toBeCloseTo(5.5, 4);
    expect(hit.normal.y).toBeCloseTo(1, 4);
    w.destroy();
  });

  it('follows bodies as they move', async () => {
    const w = await makeWorld({ gravity: { x: 0, y: 0, z: 0 } });
    w.addBox({ x: 0.5, y: 0.5, z: 0.5 }, { x: 0, y: 0, z: 0 }, null, { linearVelocity: { x: 6, y: 0, z: 0 }, linearDamping: 0 });
    run(w, 60);
    expect(w.rayDownY(0, 5, 0, 10)).toBeNull();
    expect(w.rayDownY(6, 5, 0, 10)).toBeCloseTo(0.5, 2);
    w.destroy();
  });

  it('throws a clear Error for a zero or non-finite ray', async () => {
    const w = await makeWorld();
    expect(() => w.rayCast({ x: 0, y: 0, z: 0 }, { x: 0, y: 0, z: 0 })).toThrow(/direction must be non-zero/);
    expect(() => w.rayCast({ x: Number.NaN, y: 0, z: 0 }, { x: 1, y: 0, z: 0 })).toThrow(/origin.x must be a finite number/);
    expect(() => w.rayCast({ x: 0, y: 0, z: 0 }, { x: 1, y: Number.POSITIVE_INFINITY, z: 0 })).toThrow(/direction.y/);
    expect(() => w.rayDownY(0, 0, 0, 0)).toThrow(/dist > 0/);
    expect(() => w.rayDownY(0, Number.NaN, 0, 1)).toThrow(/finite/);
    w.destroy();
  });
});
