// Tests of the layer/mask scheme: the symmetric rule, a CCD bullet that ignores its shooter's layer but stops at a
// wall, and query filters built from a layer that see exactly what that layer collides with.
import { describe, expect, it } from 'vitest';
import { CollisionLayer, layersInteract, makeBroadPhaseFilter, makeObjectLayerFilter } from '../../../shared/physics/index.ts';
import { worldInternals } from '../../../shared/physics/internal.ts';
import { assertGroupBits, packObjectLayer } from '../../../shared/physics/layers.ts';
import { makeWorld, run } from '../../helpers/physics.ts';

const { World, Player, Enemy, Bullet, Prop, Trigger, All } = CollisionLayer;

describe('layers', () => {
  it('lets two bodies interact only when each one\'s layer is in the other\'s mask', () => {
    expect(layersInteract(Bullet, World | Enemy, Player, All)).toBe(false); // the player's mask has no say
    expect(layersInteract(Player, All, Bullet, World | Enemy)).toBe(false); // symmetric
    expect(layersInteract(Bullet, World | Enemy, Enemy, All)).toBe(true);
    expect(layersInteract(Bullet, World | Enemy, World, All)).toBe(true);
    expect(layersInteract(Prop, All, Trigger, Player)).toBe(false);
    expect(layersInteract(Player | Enemy, Prop, Prop, Enemy)).toBe(true); // any shared bit on both sides
  });

  it('fires a CCD bullet through a Player and stops it at the wall behind', async () => {
    const w = await makeWorld({ gravity: { x: 0, y: 0, z: 0 } });
    const wall = w.addBox({ x: 0.05, y: 2, z: 2 }, { x: 12.3, y: 1, z: 0 }, null, { motion: 'static', restitution: 0 });
    const player = w.addBox({ x: 0.3, y: 0.9, z: 0.3 }, { x: 5, y: 1, z: 0 }, null, { layer: Player, mask: All, massKg: 80 });
    const bullet = w.addSphere(0.02, { x: 0, y: 1, z: 0 }, {
      layer: Bullet,
      mask: World | Enemy,
      motionQuality: 'linearCast',
      linearVelocity: { x: 300, y: 0, z: 0 },
      restitution: 0,
    });
    run(w, 30); // 300 m/s covers 5 m per tick: without CCD it would skip straight past the 10 cm wall
    expect(bullet.position().x).toBeLessThan(12.25); // against the wall's near face (Jolt allows ~1 cm penetration)
    expect(bullet.position().x).toBeGreaterThan(12.25 - 0.02 - 0.02);
    expect(player.position().x).toBeCloseTo(5, 6); // untouched
    expect(player.linearVelocity().x).toBe(0);
    expect(wall.position().x).toBeCloseTo(12.3, 6);
    w.destroy();
  });

  it('lets a discrete bullet at the same speed tunnel through the wall (why bullets use linearCast)', async () => {
    const w = await makeWorld({ gravity: { x: 0, y: 0, z: 0 } });
    w.addBox({ x: 0.05, y: 2, z: 2 }, { x: 12.3, y: 1, z: 0 }, null, { motion: 'static', restitution: 0 });
    const bullet = w.addSphere(0.02, { x: 0, y: 1, z: 0 }, { layer: Bullet, mask: World | Enemy, linearVelocity: { x: 300, y: 0, z: 0 }, restitution: 0 });
    run(w, 30);
    expect(bullet.position().x).toBeGreaterThan(20);
    w.destroy();
  });

  it('hits an Enemy in the bullet\'s mask and pushes it', async () => {
    const w = await makeWorld({ gravity: { x: 0, y: 0, z: 0 } });
    const enemy = w.addBox({ x: 0.3, y: 0.9, z: 0.3 }, { x: 5, y: 1, z: 0 }, null, { layer: Enemy, massKg: 1 });
    const bullet = w.addSphere(0.05, { x: 0, y: 1, z: 0 }, { layer: Bullet, mask: World | Enemy, motionQuality: 'linearCast', linearVelocity: { x: 100, y: 0, z: 0 }, massKg: 0.5 });
    run(w, 10);
    expect(enemy.linearVelocity().x).toBeGreaterThan(1);
    expect(bullet.position().x).toBeLessThan(enemy.position().x);
    w.destroy();
  });

  it('builds query filters that see exactly what the querying layer collides with', async () => {
    const w = await makeWorld();
    const J = w.jolt;
    const wall = w.addBox({ x: 0.1, y: 2, z: 2 }, { x: 10, y: 0, z: 0 }, null, { motion: 'static' });
    const player = w.addBox({ x: 0.3, y: 0.9, z: 0.3 }, { x: 5, y: 0, z: 0 }, null, { layer: Player, gravityFactor: 0 });
    const cast = (group: number, mask: number): number | undefined => {
      const objectLayer = packObjectLayer(J, group, mask);
      const bp = makeBroadPhaseFilter(J, w.filters, objectLayer);
      const obj = makeObjectLayerFilter(J, w.filters, objectLayer);
      const origin = new J.RVec3(0, 0, 0);
      const dir = new J.Vec3(20, 0, 0);
      const ray = new J.RRayCast(origin, dir);
      const settings = new J.RayCastSettings();
      const collector = new J.CastRayClosestHitCollisionCollector();
      const bodyFilter = new J.BodyFilter();
      const shapeFilter = new J.ShapeFilter();
      w.system.GetNarrowPhaseQuery().CastRay(ray, settings, collector, bp, obj, bodyFilter, shapeFilter);
      const hit = collector.HadHit() ? worldInternals(w).bodyByJoltId(collector.mHit.mBodyID.GetIndexAndSequenceNumber())?.id : undefined;
      for (const o of [bp, obj, origin, dir, ray, settings, collector, bodyFilter, shapeFilter]) J.destroy(o);
      return hit;
    };
    expect(cast(Bullet, World | Enemy)).toBe(wall.id); // through the player
    expect(cast(Enemy, All)).toBe(player.id);
    expect(cast(Player, Prop)).toBeUndefined(); // nothing in its mask on the ray
    w.destroy();
  });

  it('rejects layer and mask values outside the 16 group bits', () => {
    expect(() => assertGroupBits(0, 'layer')).toThrow(/layer must be a non-zero integer of CollisionLayer bits/);
    expect(() => assertGroupBits(0x10000, 'mask')).toThrow(/mask must be/);
    expect(() => assertGroupBits(-1, 'mask')).toThrow(/got -1/);
    expect(() => assertGroupBits(Number.NaN, 'mask')).toThrow(/got NaN/);
    expect(() => assertGroupBits(Player | Enemy, 'layer')).not.toThrow();
  });
});
