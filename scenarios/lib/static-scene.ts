// Building blocks of static scenery shared by scenarios: a ground slab, boundary walls, and axis-aligned blocks
// given by their min/max corners. Everything goes through ctx.spawn, so it gets stable ids and render colours.
import type { BodyHandle, Vec3Like } from '../../shared/physics/index.ts';
import type { Rgb, ScenarioContext } from '../../shared/sim/scenario.ts';
import { Palette } from './palette.ts';

/** A static ground slab whose top face is at y = `topY`, spanning [-halfSize, halfSize] in x and z. */
export function addGround(ctx: ScenarioContext, halfSizeMetres: number, topY = 0, color: Rgb = Palette.ground): BodyHandle {
  const thickness = 0.5;
  return ctx.spawn({ kind: 'box', halfExtents: { x: halfSizeMetres, y: thickness, z: halfSizeMetres } }, { x: 0, y: topY - thickness, z: 0 }, null, {
    motion: 'static',
    friction: 0.6,
    color,
    name: 'ground',
  });
}

/** Four static walls of `heightMetres` standing on y = 0 around the square [-halfSize, halfSize]². */
export function addBoundaryWalls(ctx: ScenarioContext, halfSizeMetres: number, heightMetres: number, color: Rgb = Palette.wall): BodyHandle[] {
  const t = 0.25;
  const h = heightMetres / 2;
  const span = halfSizeMetres + 2 * t;
  const walls: Array<[Vec3Like, Vec3Like]> = [
    [{ x: span, y: h, z: t }, { x: 0, y: h, z: -(halfSizeMetres + t) }],
    [{ x: span, y: h, z: t }, { x: 0, y: h, z: halfSizeMetres + t }],
    [{ x: t, y: h, z: halfSizeMetres }, { x: -(halfSizeMetres + t), y: h, z: 0 }],
    [{ x: t, y: h, z: halfSizeMetres }, { x: halfSizeMetres + t, y: h, z: 0 }],
  ];
  return walls.map(([half, pos], i) => ctx.spawn({ kind: 'box', halfExtents: half }, pos, null, { motion: 'static', color, name: `wall ${i}` }));
}

/** A static box filling the axis-aligned region [min, max] (m). */
export function addBlock(ctx: ScenarioContext, min: Vec3Like, max: Vec3Like, color: Rgb, name: string): BodyHandle {
  if (!(max.x > min.x && max.y > min.y && max.z > min.z)) throw new Error(`addBlock "${name}": max must exceed min on every axis`);
  const half = { x: (max.x - min.x) / 2, y: (max.y - min.y) / 2, z: (max.z - min.z) / 2 };
  const centre = { x: (max.x + min.x) / 2, y: (max.y + min.y) / 2, z: (max.z + min.z) / 2 };
  return ctx.spawn({ kind: 'box', halfExtents: half }, centre, null, { motion: 'static', friction: 0.8, color, name });
}
