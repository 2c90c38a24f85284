// terrain-balls (the seed's geo_physics): balls bounce down a mountain whose terrain is generated from the seed and
// streamed in as tiles of mesh colliders around the players and the balls still in play, and dropped behind them.
// Balls that leave the terrain are removed; the tile count never exceeds maxTiles. Streaming: terrain/tile-streamer.ts.
import type { Vec3Like } from '../shared/physics/index.ts';
import type { ScenarioContext, ScenarioDefinition, ScenarioInstance } from '../shared/sim/scenario.ts';
import { Palette, PROP_COLORS } from './lib/palette.ts';
import { meshHeightAt } from './lib/terrain-grid.ts';
import { mountainTerrain } from './lib/terrain-heights.ts';
import { TileStreamer } from './terrain/tile-streamer.ts';

/** How far below the surface a ball may be before it counts as fallen through a missing tile (m). */
const FALLEN_METRES = 3;
const SUMMIT_SPREAD_METRES = 6;

/** Balls bouncing down a streamed mountain. */
export const scenario: ScenarioDefinition = {
  name: 'terrain-balls',
  description: 'Balls bounce down a generated mountain whose mesh-collider tiles stream in around players and balls and are dropped behind them.',
  params: {
    tileCells: { default: 8, min: 2, max: 32, integer: true, description: 'cells per tile side (2 triangles each)' },
    cellSizeMetres: { default: 2, min: 0.5, max: 8, description: 'size of one terrain cell (m)' },
    viewTiles: { default: 1, min: 0, max: 4, integer: true, description: 'tiles loaded around each player and ball, in every direction' },
    maxTiles: { default: 48, min: 1, max: 400, integer: true, description: 'most tiles loaded at once' },
    buildsPerTick: { default: 4, min: 1, max: 64, integer: true, description: 'most tiles built in one tick' },
    peakMetres: { default: 40, min: 5, max: 120, description: 'height of the summit (m)' },
    mountainWidthMetres: { default: 60, min: 10, max: 300, description: 'distance from the summit at which the mountain is half as high (m)' },
    terrainRadiusMetres: { default: 160, min: 20, max: 300, description: 'how far from the summit the terrain reaches (m); balls beyond it are removed' },
    maxBalls: { default: 40, min: 0, max: 500, integer: true, description: 'most balls in play at once' },
    spawnEveryTicks: { default: 15, min: 1, max: 3600, integer: true, description: 'ticks between two new balls at the summit' },
    ballRadiusMetres: { default: 0.5, min: 0.1, max: 3, description: 'ball radius (m)' },
  },
  bounds: { min: { x: -320, y: -50, z: -320 }, max: { x: 320, y: 250, z: 320 } },
  golden: { ticks: 300, bots: 1 },
  world: { maxBodies: 2048 },
  build(ctx: ScenarioContext): ScenarioInstance {
    const p = ctx.params;
    const heightAt = mountainTerrain(ctx.rng.nextU32(), {
      peakMetres: p.peakMetres,
      halfWidthMetres: p.mountainWidthMetres,
      roughnessMetres: p.peakMetres * 0.08,
      featureMetres: 12,
    });
    const surface = (x: number, z: number): number => meshHeightAt(heightAt, x, z, p.cellSizeMetres);
    const snowLine = p.peakMetres * 0.6;
    const tiles = new TileStreamer(
      {
        heightAt,
        tileCells: p.tileCells,
        cellSizeMetres: p.cellSizeMetres,
        terrainRadiusMetres: p.terrainRadiusMetres,
        colorOf: (mean) => (mean > snowLine ? Palette.snow : Palette.terrain),
      },
      { viewTiles: p.viewTiles, maxTiles: p.maxTiles, buildsPerTick: p.buildsPerTick },
    );
    // Players start on the southern slope, a quarter of the way out; the first ones see the summit.
    const spawnRadius = Math.min(p.terrainRadiusMetres * 0.25, p.mountainWidthMetres * 0.5);
    const spawnPoint = (playerIndex: number): Vec3Like => {
      const x = ((playerIndex % 8) - 3.5) * 1.5;
      const z = spawnRadius + Math.floor(playerIndex / 8) * 1.5;
      return { x, y: surface(x, z) + 0.3, z };
    };
    // Balls in play, oldest first (ids, not handles, so checkpoints carry them), and the next spawn tick.
    let balls: number[] = [];
    let spawned = 0;
    let nextSpawnTick = 0;
    // The summit and the first spawn point are loaded before the first tick: nobody falls through at the start.
    tiles.update(ctx, [{ x: 0, y: 0, z: 0 }, spawnPoint(0)], Infinity);

    const foci = (c: ScenarioContext): Vec3Like[] => {
      const out: Vec3Like[] = c.characters().map((ch) => ch.position);
      for (const id of balls) out.push(c.world.getBody(id)!.position());
      // The summit stays in view (last in priority), so new balls always land on loaded ground.
      out.push({ x: 0, y: 0, z: 0 });
      return out;
    };

    return {
      spawnPoint,
      onTick(c: ScenarioContext) {
        const kept: number[] = [];
        for (const id of balls) {
          const ball = c.world.getBody(id);
          if (!ball) continue; // left the bounds: the simulation removed it
          const q = ball.position();
          const t = tiles.tileAt(q.x, q.z);
          const off = !tiles.inTerrain(t.tx, t.tz) || q.x * q.x + q.z * q.z > p.terrainRadiusMetres * p.terrainRadiusMetres || q.y < surface(q.x, q.z) - FALLEN_METRES;
          if (off) {
            c.remove(id);
            c.emit('ballLost', id);
          } else {
            kept.push(id);
          }
        }
        balls = kept;
        if (c.tick >= nextSpawnTick && balls.length < p.maxBalls && tiles.isLoadedAt(0, 0)) {
          const x = c.rng.range(-SUMMIT_SPREAD_METRES, SUMMIT_SPREAD_METRES);
          const z = c.rng.range(-SUMMIT_SPREAD_METRES, SUMMIT_SPREAD_METRES);
          const ball = c.spawn({ kind: 'sphere', radius: p.ballRadiusMetres }, { x, y: surface(x, z) + p.ballRadiusMetres + 1.5, z }, null, {
            motion: 'dynamic',
            restitution: 0.6,
            friction: 0.5,
            angularDamping: 0.1,
            motionQuality: 'linearCast',
            color: c.rng.pick(PROP_COLORS),
            name: `ball ${spawned}`,
          });
          balls.push(ball.id);
          spawned++;
          nextSpawnTick = c.tick + p.spawnEveryTicks;
        }
        tiles.update(c, foci(c));
      },
      saveState() {
        // [spawned, nextSpawnTick, ball count, ...ball ids, ...tile streamer state]
        return [spawned, nextSpawnTick, balls.length, ...balls, ...tiles.save()];
      },
      restoreState(state: readonly number[]) {
        const n = state[2];
        if (state.length < 3 || !Number.isInteger(n) || n < 0 || 3 + n > state.length) throw new Error('terrain-balls: bad saved state');
        spawned = state[0];
        nextSpawnTick = state[1];
        balls = state.slice(3, 3 + n);
        const end = tiles.restore(state, 3 + n);
        if (end !== state.length) throw new Error(`terrain-balls: saved state has ${state.length - end} unexpected trailing values`);
      },
    };
  },
};

