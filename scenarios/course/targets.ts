// character-course targets: light dynamic cubes on static posts behind the door, each inside a hidden sensor that
// only bullets trip ('targetHit', i). A cube knocked off its post reports 'targetDown' and is put back later.
import { CollisionLayer } from '../../shared/physics/index.ts';
import type { ScenarioContext } from '../../shared/sim/scenario.ts';
import type { SimEvent } from '../../shared/sim/types.ts';
import { Palette } from '../lib/palette.ts';

const POST_HALF = { x: 0.2, y: 0.6, z: 0.2 };
const CUBE_HALF = 0.25;
const SENSOR_HALF = 0.4;
/** Target positions: cube centres on their posts, in a row across the range. */
export const TARGET_HOMES = [2, 6, 10, 14, 18].map((z) => ({ x: 26, y: 2 * POST_HALF.y + CUBE_HALF + 0.01, z }));

interface Target {
  cubeId: number;
  sensorId: number;
  /** Tick the cube was found off its post; -1 while it stands. */
  downSinceTick: number;
}

/** The row of targets and the state checkpoints must carry. */
export class TargetRange {
  private readonly targets: Target[] = [];
  private readonly resetTicks: number;

  constructor(ctx: ScenarioContext, resetTicks: number) {
    this.resetTicks = resetTicks;
    TARGET_HOMES.forEach((home, i) => {
      ctx.spawn({ kind: 'box', halfExtents: POST_HALF }, { x: home.x, y: POST_HALF.y, z: home.z }, null, { motion: 'static', color: Palette.metal, name: `post ${i}` });
      // Only bullets trip the sensor: its mask is Bullet, and bullets' masks include Enemy.
      const sensor = ctx.spawn({ kind: 'box', halfExtents: { x: SENSOR_HALF, y: SENSOR_HALF, z: SENSOR_HALF } }, home, null, {
        motion: 'static',
        isSensor: true,
        layer: CollisionLayer.Enemy,
        mask: CollisionLayer.Bullet,
        color: Palette.target,
        hidden: true,
        name: `target sensor ${i}`,
      });
      this.targets.push({ cubeId: this.spawnCube(ctx, i), sensorId: sensor.id, downSinceTick: -1 });
    });
  }

  private spawnCube(ctx: ScenarioContext, i: number): number {
    return ctx.spawn({ kind: 'box', halfExtents: { x: CUBE_HALF, y: CUBE_HALF, z: CUBE_HALF } }, TARGET_HOMES[i], null, {
      motion: 'dynamic',
      massKg: 2,
      friction: 0.6,
      color: Palette.target,
      name: `target ${i}`,
    }).id;
  }

  /** Body ids of the target cubes, by target index. */
  cubeIds(): number[] {
    return this.targets.map((t) => t.cubeId);
  }

  /** Body ids of the target sensors, by target index. */
  sensorIds(): number[] {
    return this.targets.map((t) => t.sensorId);
  }

  /** Reports bullets entering a standing target's sensor. */
  onEvents(ctx: ScenarioContext, events: readonly SimEvent[]): void {
    for (const e of events) {
      if (e.type !== 'sensorEnter') continue;
      const i = this.targets.findIndex((t) => t.sensorId === e.sensorId);
      if (i < 0 || this.targets[i].downSinceTick >= 0) continue;
      if (ctx.world.getBody(e.bodyId)?.layer === CollisionLayer.Bullet) ctx.emit('targetHit', i);
    }
  }

  /** Notices cubes knocked off their posts and puts them back after the reset delay. */
  onTick(ctx: ScenarioContext): void {
    this.targets.forEach((t, i) => {
      const cube = ctx.world.getBody(t.cubeId);
      if (t.downSinceTick < 0) {
        const p = cube?.position();
        const home = TARGET_HOMES[i];
        const off = !p || p.y < home.y - 0.3 || (p.x - home.x) * (p.x - home.x) + (p.z - home.z) * (p.z - home.z) > 0.25;
        if (off) {
          t.downSinceTick = ctx.tick;
          ctx.emit('targetDown', i);
        }
      } else if (ctx.tick - t.downSinceTick >= this.resetTicks) {
        if (cube) ctx.remove(t.cubeId);
        t.cubeId = this.spawnCube(ctx, i);
        t.downSinceTick = -1;
        ctx.emit('targetReset', i);
      }
    });
  }

  /** [cube id, down-since tick] per target. */
  save(): number[] {
    return this.targets.flatMap((t) => [t.cubeId, t.downSinceTick]);
  }

  /** Restores what save() wrote, starting at `state[at]`; returns the index after it. */
  restore(state: readonly number[], at: number): number {
    if (at + 2 * this.targets.length > state.length) throw new Error('character-course: bad saved target state');
    this.targets.forEach((t, i) => {
      t.cubeId = state[at + 2 * i];
      t.downSinceTick = state[at + 2 * i + 1];
    });
    return at + 2 * this.targets.length;
  }
}
