// Tests for scenarios/terrain-balls.ts (with terrain/tile-streamer.ts): the streamed mountain's first tiles, crack-free
// tile edges, parameter checks, tiles following a walking player and the balls within maxTiles, balls leaving the
// terrain being removed, state round trips and seed determinism.
import { describe, expect, it } from 'vitest';
import { scenario } from '../../scenarios/terrain-balls.ts';
import { expectParamsValidated, expectSeedDeterminism } from '../helpers/scenario-checks.ts';
import { ScenarioHarness } from '../helpers/scenario-harness.ts';
import { expectSimulationReplays } from '../helpers/scenario-sim.ts';

/** A small, fast mountain: 8 m tiles, a 60 m terrain disc. */
const SMALL = { tileCells: 4, cellSizeMetres: 2, maxTiles: 12, peakMetres: 15, mountainWidthMetres: 20, terrainRadiusMetres: 60, maxBalls: 6, spawnEveryTicks: 10 };

function tiles(h: ScenarioHarness) {
  return h.scenarioBodyIds()
    .map((id) => h.world.getBody(id)!)
    .filter((b) => b.name?.startsWith('tile '));
}

function balls(h: ScenarioHarness) {
  return h.dynamicBodies().filter((b) => b.name?.startsWith('ball '));
}

describe('terrain-balls', () => {
  it('builds with defaults: mesh tiles around the summit and the first spawn point, then balls at the summit', async () => {
    const h = await ScenarioHarness.create(scenario);
    try {
      const first = tiles(h);
      expect(first.length).toBeGreaterThanOrEqual(9);
      expect(first.length).toBeLessThanOrEqual(18);
      expect(first.every((t) => t.motion === 'static' && t.shape?.kind === 'mesh')).toBe(true);
      expect(h.world.rayDownY(0, 200, 0, 400, true)).toBeGreaterThan(scenario.params.peakMetres.default * 0.8);
      const s = h.instance.spawnPoint(0);
      expect(h.world.rayDownY(s.x, s.y + 2, s.z, 10, true)).not.toBeNull();
      h.run(1);
      expect(balls(h)).toHaveLength(1);
    } finally {
      h.destroy();
    }
  });

  it('rejects unknown and out-of-range parameters with a clear Error', async () => {
    await expectParamsValidated(scenario);
  });

  it('joins neighbouring tiles without cracks', async () => {
    const h = await ScenarioHarness.create(scenario, { params: SMALL });
    try {
      // Rays straight down exactly on and just beside the tile borders (every 8 m) all hit the terrain.
      let rays = 0;
      for (const x of [-8, -0.001, 0, 0.001, 8]) {
        for (let z = -7.9; z < 7.9; z += 0.37) {
          expect(h.world.rayDownY(x, 100, z, 200, true), `(${x}, ${z})`).not.toBeNull();
          expect(h.world.rayDownY(z, 100, x, 200, true), `(${z}, ${x})`).not.toBeNull();
          rays += 2;
        }
      }
      expect(rays).toBeGreaterThan(200);
    } finally {
      h.destroy();
    }
  });

  it('streams tiles in ahead of a walking player and drops them behind, never above maxTiles', async () => {
    const h = await ScenarioHarness.create(scenario, { params: { ...SMALL, maxBalls: 0, terrainRadiusMetres: 120 } });
    try {
      h.join(1);
      const start = h.controller(1).position;
      // Sprint towards +z (moveZ back at yaw 0), down the mountain and away from the summit.
      h.setInput(1, { moveZ: -127, buttons: 4 });
      const seen = new Set<number>();
      for (let t = 0; t < 600; t++) {
        h.step();
        const now = tiles(h);
        expect(now.length).toBeLessThanOrEqual(SMALL.maxTiles);
        now.forEach((b) => seen.add(b.id));
        const p = h.controller(1).position;
        expect(h.world.rayDownY(p.x, p.y + 1, p.z, 5, true), `ground under the player at tick ${t}`).not.toBeNull();
      }
      const end = h.controller(1).position;
      expect(end.z - start.z).toBeGreaterThan(40);
      expect(seen.size).toBeGreaterThan(tiles(h).length + 5);
      // The ground the player started on is gone again (it is far from both the player and the summit).
      expect(h.world.rayDownY(start.x, start.y + 1, start.z + 4, 50, true)).toBeNull();
      expect(h.events.filter((e) => e.type === 'bodyRemoved').length).toBeGreaterThan(0);
    } finally {
      h.destroy();
    }
  });

  it('keeps loaded ground under the balls in play while they roll down, within maxTiles', async () => {
    const h = await ScenarioHarness.create(scenario, { params: SMALL });
    try {
      let farthest = 0;
      for (let t = 0; t < 600; t++) {
        h.step();
        expect(tiles(h).length).toBeLessThanOrEqual(SMALL.maxTiles);
        for (const b of balls(h)) {
          const p = b.position();
          farthest = Math.max(farthest, Math.sqrt(p.x * p.x + p.z * p.z));
          expect(h.world.rayDownY(p.x, p.y, p.z, 20, true), `ground under ${b.name} at tick ${t}`).not.toBeNull();
        }
      }
      expect(farthest).toBeGreaterThan(15);
    } finally {
      h.destroy();
    }
  });

  it('removes balls that leave the terrain and keeps dropping new ones', async () => {
    const h = await ScenarioHarness.create(scenario, { params: { ...SMALL, terrainRadiusMetres: 20, peakMetres: 25 } });
    try {
      h.run(900);
      const lost = h.scenarioEvents('ballLost');
      expect(lost.length).toBeGreaterThan(0);
      for (const e of lost) {
        expect(h.world.getBody(e.value)).toBeUndefined();
        expect(h.events.some((r) => r.type === 'bodyRemoved' && r.bodyId === e.value && r.tick === e.tick)).toBe(true);
      }
      for (const b of balls(h)) {
        const p = b.position();
        expect(p.x * p.x + p.z * p.z).toBeLessThanOrEqual(20 * 20);
      }
      expect(balls(h).length).toBeGreaterThan(0);
    } finally {
      h.destroy();
    }
  });

  it('round-trips its scenario state and rejects a malformed one', async () => {
    const h = await ScenarioHarness.create(scenario, { params: SMALL });
    try {
      h.run(25);
      const saved = h.instance.saveState!();
      expect(saved.slice(0, 3)).toEqual([3, 30, 3]);
      h.run(40);
      h.instance.restoreState!(saved);
      expect(h.instance.saveState!()).toEqual(saved);
      expect(() => h.instance.restoreState!([...saved, 0])).toThrow(/unexpected trailing values/);
      expect(() => h.instance.restoreState!([0, 0, 5, 1])).toThrow(/terrain-balls: bad saved state/);
    } finally {
      h.destroy();
    }
  });

  it('gives identical bodies for one seed and different ones for another', async () => {
    await expectSeedDeterminism(scenario, SMALL, 120);
  });
  it('runs deterministically through the Simulation with bots, across checkpoint rollbacks', async () => {
    await expectSimulationReplays(scenario, SMALL, 150, 2);
  });
});
