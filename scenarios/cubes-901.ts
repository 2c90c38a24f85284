// cubes-901: a 30 × 30 field of small cubes on a plane plus one large cube that the first player (lowest player id)
// rolls through them with their move axes (spin towards the walk direction plus a push). The snapshot-bandwidth scene.
import type { Vec3Like } from '../shared/physics/index.ts';
import { walkVelocity } from '../shared/sim/controls.ts';
import { Button } from '../shared/sim/input.ts';
import type { ScenarioContext, ScenarioDefinition, ScenarioInstance } from '../shared/sim/scenario.ts';
import { TICK_DT_SECONDS } from '../shared/tick-rate.ts';
import { Palette, PROP_COLORS } from './lib/palette.ts';
import { addGround } from './lib/static-scene.ts';

const GROUND_HALF_METRES = 40;
const BIG_HALF_METRES = 1;
const BIG_MASS_KG = 200;
const SMALL_MASS_KG = 5;
/** Spin rate the big cube is driven towards at full stick (rad/s), and how fast it gets there (rad/s²). */
const SPIN_RAD_PER_SECOND = 3;
const SPIN_ACCEL_RAD_PER_SECOND2 = 12;
/** Extra push at full stick (m/s²) while slower than PUSH_MAX_SPEED. */
const PUSH_ACCEL = 6;
const PUSH_MAX_SPEED = 6;
const HOP_SPEED_METRES_PER_SECOND = 5;

/** 900 small cubes and one player-driven big cube. */
export const scenario: ScenarioDefinition = {
  name: 'cubes-901',
  description: 'A 30 × 30 field of small cubes and one large cube the first player rolls through them: the snapshot-bandwidth scene.',
  params: {
    side: { default: 30, min: 1, max: 60, integer: true, description: 'small cubes per side of the square field' },
    cubeSizeMetres: { default: 0.5, min: 0.1, max: 1, description: 'edge of a small cube (m)' },
    spacingMetres: { default: 1, min: 0.2, max: 3, description: 'distance between neighbouring small cubes (m); at least the cube size' },
  },
  bounds: { min: { x: -GROUND_HALF_METRES - 2, y: -10, z: -GROUND_HALF_METRES - 2 }, max: { x: GROUND_HALF_METRES + 2, y: 40, z: GROUND_HALF_METRES + 2 } },
  golden: { ticks: 300, bots: 1 },
  world: { maxBodyPairs: 32768, maxContactConstraints: 16384 },
  build(ctx: ScenarioContext): ScenarioInstance {
    const p = ctx.params;
    if (p.spacingMetres < p.cubeSizeMetres) {
      throw new Error(`scenario cubes-901: parameter spacingMetres (${p.spacingMetres}) must be at least cubeSizeMetres (${p.cubeSizeMetres})`);
    }
    const fieldHalf = ((p.side - 1) * p.spacingMetres) / 2;
    if (fieldHalf + 6 > GROUND_HALF_METRES) {
      throw new Error(`scenario cubes-901: a field of ${p.side} cubes ${p.spacingMetres} m apart does not fit the ${2 * GROUND_HALF_METRES} m ground`);
    }
    addGround(ctx, GROUND_HALF_METRES);
    const half = p.cubeSizeMetres / 2;
    for (let row = 0; row < p.side; row++) {
      for (let col = 0; col < p.side; col++) {
        ctx.spawn({ kind: 'box', halfExtents: { x: half, y: half, z: half } }, { x: -fieldHalf + col * p.spacingMetres, y: half, z: -fieldHalf + row * p.spacingMetres }, null, {
          motion: 'dynamic',
          massKg: SMALL_MASS_KG,
          friction: 0.5,
          color: PROP_COLORS[(row + col) % PROP_COLORS.length],
          name: `cube ${row}.${col}`,
        });
      }
    }
    const bigStart: Vec3Like = { x: 0, y: BIG_HALF_METRES, z: fieldHalf + half + 3 };
    const spawnBig = (c: ScenarioContext): number =>
      c.spawn({ kind: 'box', halfExtents: { x: BIG_HALF_METRES, y: BIG_HALF_METRES, z: BIG_HALF_METRES } }, bigStart, null, {
        motion: 'dynamic',
        massKg: BIG_MASS_KG,
        friction: 1,
        angularDamping: 0.5,
        color: Palette.player,
        name: 'big cube',
      }).id;
    let bigId = spawnBig(ctx);

    return {
      spawnPoint(playerIndex: number) {
        const slot = playerIndex % 10;
        return { x: -4.5 + slot, y: 0.05, z: bigStart.z + 3 };
      },
      onTick(c: ScenarioContext) {
        let big = c.world.getBody(bigId);
        if (!big) {
          // It rolled off the world and the simulation removed it: put a new one at the start.
          bigId = spawnBig(c);
          big = c.world.getBody(bigId)!;
        }
        const driver = c.inputs()[0];
        if (!driver) return;
        const cmd = driver.input;
        const dir = walkVelocity(cmd, 1, (cmd.buttons & Button.Sprint) !== 0);
        const w = big.angularVelocity();
        const v = big.linearVelocity();
        if (dir.x !== 0 || dir.z !== 0) {
          // Rolling towards d means spinning about up × d = (d.z, 0, -d.x); approach that spin at a bounded rate.
          const maxStep = SPIN_ACCEL_RAD_PER_SECOND2 * TICK_DT_SECONDS;
          const towards = (current: number, goal: number): number => current + Math.max(-maxStep, Math.min(maxStep, goal - current));
          c.world.setAngularVelocity(bigId, { x: towards(w.x, dir.z * SPIN_RAD_PER_SECOND), y: w.y, z: towards(w.z, -dir.x * SPIN_RAD_PER_SECOND) });
          if (v.x * v.x + v.z * v.z < PUSH_MAX_SPEED * PUSH_MAX_SPEED) {
            const k = BIG_MASS_KG * PUSH_ACCEL * TICK_DT_SECONDS;
            c.world.addImpulse(bigId, { x: dir.x * k, y: 0, z: dir.z * k });
          }
        }
        if ((cmd.buttons & Button.Jump) !== 0 && big.position().y < BIG_HALF_METRES * 1.5 && v.y < 0.5) {
          c.world.addImpulse(bigId, { x: 0, y: BIG_MASS_KG * HOP_SPEED_METRES_PER_SECOND, z: 0 });
        }
      },
      saveState() {
        return [bigId];
      },
      restoreState(state: readonly number[]) {
        if (state.length !== 1 || !Number.isInteger(state[0]) || state[0] < 1) throw new Error(`cubes-901: bad saved state ${JSON.stringify(state)}`);
        bigId = state[0];
      },
    };
  },
};
