// Dropping rolling things onto generated terrain: mostly balls, some boxes, capsules and hulls, at random spots
// above the surface. Shared by mesh-terrain and height-field; draws only from the scenario's Prng.
import type { BodyHandle, ShapeSpec } from '../../shared/physics/index.ts';
import type { ScenarioContext, ScenarioInstance } from '../../shared/sim/scenario.ts';
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

/**
 * The live side shared by the terrain scenes: players spawn on a 4×4 grid just above the surface, and `perTick`
 * things are dropped onto the terrain each tick until `total` have fallen. Its state (the count dropped) is saved.
 */
export function terrainDropInstance(scene: string, surface: HeightFn, spreadMetres: number, spawnClearanceMetres: number, perTick: number, total: number): ScenarioInstance {
  let dropped = 0;
  return {
    spawnPoint(playerIndex: number) {
      const x = ((playerIndex % 4) - 1.5) * 1.5;
      const z = (Math.floor(playerIndex / 4) % 4) * 1.5 - 2;
      return { x, y: surface(x, z) + spawnClearanceMetres, z };
    },
    onTick(c: ScenarioContext) {
      for (let i = 0; i < perTick && dropped < total; i++) {
        dropOnTerrain(c, surface, spreadMetres, 3, 0.35, `roller ${dropped}`);
        dropped++;
      }
    },
    saveState() {
      return [dropped];
    },
    restoreState(state: readonly number[]) {
      if (state.length !== 1 || !Number.isInteger(state[0]) || state[0] < 0) throw new Error(`${scene}: bad saved state ${JSON.stringify(state)}`);
      dropped = state[0];
    },
  };
}
