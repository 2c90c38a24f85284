// Dropping rolling things onto generated terrain: mostly balls, some boxes, capsules and hulls, at random spots
// above the surface. Shared by mesh-terrain and height-field; draws only from the scenario's Prng.
import type { BodyHandle, ShapeSpec } from '../../shared/physics/index.ts';
import type { ScenarioContext } from '../../shared/sim/scenario.ts';
import { PROP_COLORS } from './palette.ts';
import { randomMixedShape, randomUnitQuat } from './random-shapes.ts';
import type { HeightFn } from './terrain-grid.ts';

/** Drops one body above a random point of the square [-spreadMetres, spreadMetres]², `dropHeightMetres` above the surface. */
export function dropOnTerrain(ctx: ScenarioContext, heightAt: HeightFn, spreadMetres: number, dropHeightMetres: number, sizeMetres: number, name: string): BodyHandle {
  const rng = ctx.rng;
  const shape: ShapeSpec = rng.next() < 0.65 ? { kind: 'sphere', radius: sizeMetres * rng.range(0.6, 1) } : randomMixedShape(rng, sizeMetres);
  const x = rng.range(-spreadMetres, spreadMetres);
  const z = rng.range(-spreadMetres, spreadMetres);
  const rot = randomUnitQuat(rng);
  return ctx.spawn(shape, { x, y: heightAt(x, z) + dropHeightMetres, z }, rot, {
    motion: 'dynamic',
    friction: 0.6,
    restitution: 0.3,
    // Damping stands in for rolling resistance, so balls come to rest in the hollows instead of rocking for ever.
    angularDamping: shape.kind === 'sphere' || shape.kind === 'capsule' ? 2 : 0.3,
    linearDamping: 0.2,
    color: rng.pick(PROP_COLORS),
    name,
  });
}
