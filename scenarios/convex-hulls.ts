// convex-hulls: assorted random convex hulls built from seeded point clouds (rocks, shards, slabs, crystals) are
// dropped a few per tick onto a walled ground, where they tumble and settle.
import type { Vec3Like } from '../shared/physics/index.ts';
import { detCos, detSin } from '../shared/sim/det-math.ts';
import type { Prng } from '../shared/sim/prng.ts';
import type { Rgb, ScenarioContext, ScenarioDefinition, ScenarioInstance } from '../shared/sim/scenario.ts';
import { randomHullPoints, randomUnitQuat } from './lib/random-shapes.ts';
import { addBoundaryWalls, addGround } from './lib/static-scene.ts';

/** Hull styles: how the point cloud's ellipsoid is proportioned, and the colour it is drawn in. */
const STYLES: ReadonlyArray<{ name: string; radii: (rng: Prng) => Vec3Like; color: Rgb }> = [
  { name: 'rock', radii: (r) => ({ x: r.range(0.7, 1), y: r.range(0.6, 0.9), z: r.range(0.7, 1) }), color: [0.55, 0.5, 0.45] },
  { name: 'shard', radii: (r) => ({ x: r.range(0.25, 0.4), y: r.range(1.2, 1.8), z: r.range(0.25, 0.4) }), color: [0.35, 0.7, 0.85] },
  { name: 'slab', radii: (r) => ({ x: r.range(0.9, 1.3), y: r.range(0.2, 0.3), z: r.range(0.6, 1) }), color: [0.8, 0.55, 0.3] },
  { name: 'crystal', radii: (r) => ({ x: r.range(0.4, 0.6), y: r.range(0.9, 1.3), z: r.range(0.4, 0.6) }), color: [0.7, 0.4, 0.85] },
];

/** Points of a bipyramid (two apexes on y plus a ring of `ring` jittered points around them): a crystal-like hull. */
function crystalPoints(rng: Prng, radii: Vec3Like, ring: number): number[] {
  const out = [0, radii.y, 0, 0, -radii.y, 0];
  const step = (2 * Math.PI) / ring;
  for (let i = 0; i < ring; i++) {
    // Evenly spread ring angles (jittered by under half a step) keep the origin inside the hull.
    const angle = (i + rng.range(-0.4, 0.4)) * step;
    const r = rng.range(0.8, 1);
    out.push(detCos(angle) * radii.x * r, rng.range(-0.15, 0.15) * radii.y, detSin(angle) * radii.z * r);
  }
  return out;
}

/** Random convex hulls dropped on a ground. */
export const scenario: ScenarioDefinition = {
  name: 'convex-hulls',
  description: 'Assorted random convex hulls (rocks, shards, slabs, crystals) from seeded point clouds tumble onto a walled ground.',
  params: {
    count: { default: 150, min: 1, max: 2000, integer: true, description: 'hulls dropped in total' },
    spawnPerTick: { default: 3, min: 1, max: 100, integer: true, description: 'hulls dropped per tick until count is reached' },
    minPoints: { default: 6, min: 4, max: 64, integer: true, description: 'fewest points in one hull’s cloud' },
    maxPoints: { default: 24, min: 4, max: 64, integer: true, description: 'most points in one hull’s cloud' },
    sizeMetres: { default: 0.4, min: 0.1, max: 1.5, description: 'typical half-size of a hull (m)' },
    areaMetres: { default: 14, min: 4, max: 50, description: 'side of the square the hulls fall onto (m)' },
  },
  bounds: { min: { x: -40, y: -10, z: -40 }, max: { x: 40, y: 60, z: 40 } },
  golden: { ticks: 240, bots: 1 },
  world: { maxBodyPairs: 32768, maxContactConstraints: 16384 },
  build(ctx: ScenarioContext): ScenarioInstance {
    const p = ctx.params;
    if (p.minPoints > p.maxPoints) throw new Error(`scenario convex-hulls: parameter minPoints (${p.minPoints}) must not exceed maxPoints (${p.maxPoints})`);
    const half = p.areaMetres / 2;
    addGround(ctx, half + 4);
    addBoundaryWalls(ctx, half + 3, 1.5);
    let dropped = 0;
    return {
      spawnPoint(playerIndex: number) {
        const slot = playerIndex % 16;
        return { x: -half + 0.5 + (slot % 8) * ((2 * half - 1) / 7), y: 0.05, z: half + 1.5 + (slot >= 8 ? 1 : 0) };
      },
      onTick(c: ScenarioContext) {
        for (let i = 0; i < p.spawnPerTick && dropped < p.count; i++) {
          const style = c.rng.pick(STYLES);
          const r = style.radii(c.rng);
          const radii = { x: r.x * p.sizeMetres, y: r.y * p.sizeMetres, z: r.z * p.sizeMetres };
          const n = c.rng.int(p.minPoints, p.maxPoints);
          const points = style.name === 'crystal' ? crystalPoints(c.rng, radii, Math.max(3, n - 2)) : randomHullPoints(c.rng, radii, n);
          const pos = { x: c.rng.range(-half, half), y: 6 + c.rng.range(0, 3), z: c.rng.range(-half, half) };
          c.spawn({ kind: 'convexHull', points }, pos, randomUnitQuat(c.rng), {
            motion: 'dynamic',
            friction: 0.6,
            restitution: 0.15,
            color: style.color,
            name: `${style.name} ${dropped}`,
          });
          dropped++;
        }
      },
      saveState() {
        return [dropped];
      },
      restoreState(state: readonly number[]) {
        if (state.length !== 1 || !Number.isInteger(state[0]) || state[0] < 0) throw new Error(`convex-hulls: bad saved state ${JSON.stringify(state)}`);
        dropped = state[0];
      },
    };
  },
};
