// character-course static layout: ground, stairs (0.25 m steps) and a ramp up to a deck, the far ledge across the
// platform gap, the wall with its doorway, the range backstop and a crate stack. Coordinates and builders only.
import { detAtan2, quatFromAxisAngle } from '../../shared/sim/det-math.ts';
import type { ScenarioContext } from '../../shared/sim/scenario.ts';
import { Palette, PROP_COLORS } from '../lib/palette.ts';
import { addBlock, addGround } from '../lib/static-scene.ts';

/** Half-size of the square ground (m). */
export const GROUND_HALF_METRES = 30;
/** Rise of one stair step (m): the character steps up it without jumping. */
export const STEP_RISE_METRES = 0.25;
const STEP_RUN_METRES = 0.5;
const STEP_COUNT = 8;
/** Height of the deck the stairs and the ramp lead to (m). */
export const DECK_HEIGHT_METRES = STEP_RISE_METRES * STEP_COUNT;
/** The deck and the far ledge: the moving platform shuttles across the gap between them (along z). */
export const DECK = { minX: -9, maxX: 9, minZ: -6, maxZ: -2 } as const;
export const FAR_LEDGE = { minX: -4, maxX: 4, minZ: -18, maxZ: -14 } as const;
/** The stairs' footprint: 8 steps climbing towards -z up to the deck. */
export const STAIRS = { minX: -9, maxX: -5, startZ: 2 } as const;
/** The ramp's footprint: from the ground at z = 4 up to the deck edge at z = -2. */
export const RAMP = { minX: 5, maxX: 9, lowZ: 4, highZ: -2 } as const;
/** The wall along x = 14 and its doorway (the sliding door fills it). */
export const WALL = { x: 14, halfThickness: 0.25, minZ: -20, maxZ: 20, height: 3 } as const;
export const DOORWAY = { minZ: 8.75, maxZ: 11.25, height: 2.6 } as const;
/** Where players appear: a pad in front of the stairs and ramp, facing -z (yaw 0). */
export const SPAWN = { x: 0, z: 10 } as const;

/** Builds every static part of the course. */
export function buildCourseLayout(ctx: ScenarioContext): void {
  addGround(ctx, GROUND_HALF_METRES);
  // Stairs: each step is a solid block from the ground up to its tread.
  for (let i = 0; i < STEP_COUNT; i++) {
    addBlock(
      ctx,
      { x: STAIRS.minX, y: 0, z: STAIRS.startZ - (i + 1) * STEP_RUN_METRES },
      { x: STAIRS.maxX, y: (i + 1) * STEP_RISE_METRES, z: STAIRS.startZ - i * STEP_RUN_METRES },
      Palette.stone,
      `stair ${i + 1}`,
    );
  }
  addBlock(ctx, { x: DECK.minX, y: 0, z: DECK.minZ }, { x: DECK.maxX, y: DECK_HEIGHT_METRES, z: DECK.maxZ }, Palette.stone, 'deck');
  addBlock(ctx, { x: FAR_LEDGE.minX, y: 0, z: FAR_LEDGE.minZ }, { x: FAR_LEDGE.maxX, y: DECK_HEIGHT_METRES, z: FAR_LEDGE.maxZ }, Palette.stone, 'far ledge');
  buildRamp(ctx);
  // The wall, in two pieces either side of the doorway, with a lintel over it.
  const wx = { min: WALL.x - WALL.halfThickness, max: WALL.x + WALL.halfThickness };
  addBlock(ctx, { x: wx.min, y: 0, z: WALL.minZ }, { x: wx.max, y: WALL.height, z: DOORWAY.minZ }, Palette.wall, 'wall south');
  addBlock(ctx, { x: wx.min, y: 0, z: DOORWAY.maxZ }, { x: wx.max, y: WALL.height, z: WALL.maxZ }, Palette.wall, 'wall north');
  addBlock(ctx, { x: wx.min, y: DOORWAY.height, z: DOORWAY.minZ }, { x: wx.max, y: WALL.height, z: DOORWAY.maxZ }, Palette.wall, 'lintel');
  // The backstop behind the targets catches stray bullets and knocked-off targets.
  addBlock(ctx, { x: 28.5, y: 0, z: -2 }, { x: 29, y: 4, z: 22 }, Palette.wood, 'backstop');
}

function buildRamp(ctx: ScenarioContext): void {
  const run = RAMP.lowZ - RAMP.highZ;
  const angle = detAtan2(DECK_HEIGHT_METRES, run);
  const length = Math.sqrt(run * run + DECK_HEIGHT_METRES * DECK_HEIGHT_METRES);
  const halfThickness = 0.15;
  const rot = quatFromAxisAngle({ x: 1, y: 0, z: 0 }, angle);
  // The slab's top face runs from (lowZ, 0) to (highZ, deck height); its centre sits half a thickness below that face.
  const normalY = run / length;
  const normalZ = DECK_HEIGHT_METRES / length;
  const centre = {
    x: (RAMP.minX + RAMP.maxX) / 2,
    y: DECK_HEIGHT_METRES / 2 - normalY * halfThickness,
    z: (RAMP.lowZ + RAMP.highZ) / 2 - normalZ * halfThickness,
  };
  ctx.spawn({ kind: 'box', halfExtents: { x: (RAMP.maxX - RAMP.minX) / 2, y: halfThickness, z: length / 2 } }, centre, rot, {
    motion: 'static',
    friction: 0.8,
    color: Palette.stone,
    name: 'ramp',
  });
}

/** A pyramid of crates beside the spawn pad, for pushing and shooting. */
export function buildCrates(ctx: ScenarioContext, rows: number): number[] {
  const half = 0.3;
  const ids: number[] = [];
  for (let row = 0; row < rows; row++) {
    for (let i = 0; i < rows - row; i++) {
      const x = -6 + (i - (rows - row - 1) / 2) * (2 * half + 0.02);
      const y = half + row * 2 * half;
      const crate = ctx.spawn({ kind: 'box', halfExtents: { x: half, y: half, z: half } }, { x, y, z: 8 }, null, {
        motion: 'dynamic',
        friction: 0.6,
        massKg: 20,
        color: PROP_COLORS[(row + i) % PROP_COLORS.length],
        name: `crate ${row}.${i}`,
      });
      ids.push(crate.id);
    }
  }
  return ids;
}
