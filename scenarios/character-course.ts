// character-course: the default scene. Stairs (0.25 m steps) and a ramp up to a deck, a kinematic platform
// shuttling across a gap to a far ledge, a wall whose door slides open when a player steps into its trigger zone,
// and a target range behind the door. Static layout in course/layout.ts; door and targets in their own files.
import { detCos } from '../shared/sim/det-math.ts';
import type { SimEvent } from '../shared/sim/types.ts';
import type { ScenarioContext, ScenarioDefinition, ScenarioInstance } from '../shared/sim/scenario.ts';
import { SlidingDoor } from './course/door.ts';
import { buildCourseLayout, buildCrates, DECK, DECK_HEIGHT_METRES, FAR_LEDGE, GROUND_HALF_METRES, SPAWN } from './course/layout.ts';
import { TargetRange } from './course/targets.ts';
import { Palette } from './lib/palette.ts';

const PLATFORM_HALF = { x: 1.5, y: 0.15, z: 1.5 };
const TWO_PI = 6.283185307179586;

/**
 * Centre of the moving platform at `tick`: a smooth back-and-forth along z between the deck edge and the far ledge
 * (cosine easing, so it lingers at each end for riders to step on and off).
 */
export function platformCentre(tick: number, periodTicks: number): { x: number; y: number; z: number } {
  const nearZ = DECK.minZ - PLATFORM_HALF.z;
  const farZ = FAR_LEDGE.maxZ + PLATFORM_HALF.z;
  const phase = (tick % periodTicks) / periodTicks;
  const t = (1 - detCos(TWO_PI * phase)) / 2; // 0 at the deck, 1 at the far ledge
  return { x: 0, y: DECK_HEIGHT_METRES - PLATFORM_HALF.y, z: nearZ + (farZ - nearZ) * t };
}

/** The default course: stairs, ramp, moving platform, door with trigger zone, target range. */
export const scenario: ScenarioDefinition = {
  name: 'character-course',
  description: 'A small course for characters: stairs and a ramp to a deck, a moving platform across a gap, a door that opens when you step up to it, and targets to shoot.',
  params: {
    platformPeriodTicks: { default: 360, min: 60, max: 3600, integer: true, description: 'ticks for the platform’s round trip' },
    doorCloseDelayTicks: { default: 90, min: 0, max: 3600, integer: true, description: 'ticks the door stays open after the last player leaves its zone' },
    targetResetTicks: { default: 180, min: 1, max: 3600, integer: true, description: 'ticks before a knocked-off target is put back' },
    crateRows: { default: 3, min: 0, max: 8, integer: true, description: 'rows in the crate pyramid beside the spawn pad' },
  },
  bounds: { min: { x: -GROUND_HALF_METRES - 2, y: -10, z: -GROUND_HALF_METRES - 2 }, max: { x: GROUND_HALF_METRES + 2, y: 40, z: GROUND_HALF_METRES + 2 } },
  golden: { ticks: 300, bots: 3 },
  players: { walkSpeedMetresPerSecond: 4, jumpSpeedMetresPerSecond: 5.5, bulletsHitPlayers: false },
  build(ctx: ScenarioContext): ScenarioInstance {
    const p = ctx.params;
    buildCourseLayout(ctx);
    const door = new SlidingDoor(ctx, p.doorCloseDelayTicks);
    const targets = new TargetRange(ctx, p.targetResetTicks);
    buildCrates(ctx, p.crateRows);
    const platformId = ctx.spawn({ kind: 'box', halfExtents: PLATFORM_HALF }, platformCentre(0, p.platformPeriodTicks), null, {
      motion: 'kinematic',
      friction: 1,
      color: Palette.platform,
      name: 'platform',
    }).id;
    // The first step carries the platform to its tick-1 place; each onTick then aims it one step further.
    ctx.world.moveKinematic(platformId, platformCentre(1, p.platformPeriodTicks), null);

    return {
      spawnPoint(playerIndex: number) {
        const slot = playerIndex % 14;
        return { x: SPAWN.x + ((slot % 7) - 3) * 1, y: 0.05, z: SPAWN.z + Math.floor(slot / 7) * 1.2 };
      },
      onTick(c: ScenarioContext) {
        // After the step of tick T the platform is at platformCentre(T + 1); aim it at T + 2 for the next step.
        c.world.moveKinematic(platformId, platformCentre(c.tick + 2, p.platformPeriodTicks), null);
        door.onTick(c);
        targets.onTick(c);
      },
      onEvents(c: ScenarioContext, events: readonly SimEvent[]) {
        door.onEvents(c, events);
        targets.onEvents(c, events);
      },
      saveState() {
        const d = door.save();
        return [d.length, ...d, ...targets.save()];
      },
      restoreState(state: readonly number[]) {
        if (state.length < 1 || !Number.isInteger(state[0]) || state[0] + 1 > state.length) throw new Error('character-course: bad saved state');
        door.restore(state, 1);
        const end = targets.restore(state, 1 + state[0]);
        if (end !== state.length) throw new Error(`character-course: saved state has ${state.length - end} unexpected trailing values`);
      },
    };
  },
};

