// Tests for scenarios/terrain/tile-streamer.ts on a recording fake context (no Jolt): tile priority, the maxTiles and
// per-tick build limits, dropping tiles behind a moving focus with a one-ring margin, the terrain disc, and state.
import { describe, expect, it } from 'vitest';
import { TileStreamer } from '../../../scenarios/terrain/tile-streamer.ts';
import type { ScenarioContext } from '../../../shared/sim/scenario.ts';

/** A context that records spawns and removals of tile bodies. */
function fakeContext(): { ctx: ScenarioContext; live: Map<number, string>; removed: number[] } {
  const live = new Map<number, string>();
  const removed: number[] = [];
  let next = 1;
  const ctx = {
    world: { getBody: (id: number) => (live.has(id) ? { id } : undefined) },
    spawn: (_shape: unknown, _pos: unknown, _rot: unknown, opts: { name: string }) => {
      const id = next++;
      live.set(id, opts.name);
      return { id };
    },
    remove: (id: number) => {
      if (!live.delete(id)) throw new Error(`no body ${id}`);
      removed.push(id);
    },
  } as unknown as ScenarioContext;
  return { ctx, live, removed };
}

const GRID = { heightAt: () => 0, tileCells: 2, cellSizeMetres: 5, terrainRadiusMetres: 1000, colorOf: () => [0, 0, 0] as const };

describe('tile-streamer', () => {
  it('loads the 3 × 3 tiles around a focus, named by tile coordinates', () => {
    const { ctx, live } = fakeContext();
    const s = new TileStreamer(GRID, { viewTiles: 1, maxTiles: 50, buildsPerTick: 50 });
    expect(s.update(ctx, [{ x: 15, y: 0, z: -5 }])).toEqual({ built: 9, dropped: 0 });
    expect([...live.values()].sort()).toEqual(['tile 0,-2', 'tile 0,-1', 'tile 0,0', 'tile 1,-2', 'tile 1,-1', 'tile 1,0', 'tile 2,-2', 'tile 2,-1', 'tile 2,0'].sort());
    expect(s.isLoadedAt(15, -5)).toBe(true);
    expect(s.isLoadedAt(35, -5)).toBe(false);
  });

  it('loads every focus’s own tile before any neighbour when maxTiles is tight', () => {
    const { ctx, live } = fakeContext();
    const s = new TileStreamer(GRID, { viewTiles: 2, maxTiles: 6, buildsPerTick: 50 });
    const foci = [0, 100, 200, 300, 400].map((x) => ({ x: x + 1, y: 0, z: 1 }));
    s.update(ctx, foci);
    expect(live.size).toBe(6);
    for (const f of foci) expect(s.isLoadedAt(f.x, f.z)).toBe(true);
  });

  it('builds at most buildsPerTick tiles per update, most urgent first', () => {
    const { ctx } = fakeContext();
    const s = new TileStreamer(GRID, { viewTiles: 1, maxTiles: 50, buildsPerTick: 2 });
    expect(s.update(ctx, [{ x: 1, y: 0, z: 1 }]).built).toBe(2);
    expect(s.isLoadedAt(1, 1)).toBe(true);
    s.update(ctx, [{ x: 1, y: 0, z: 1 }]);
    s.update(ctx, [{ x: 1, y: 0, z: 1 }]);
    s.update(ctx, [{ x: 1, y: 0, z: 1 }]);
    expect(s.count).toBe(8);
    s.update(ctx, [{ x: 1, y: 0, z: 1 }]);
    expect(s.count).toBe(9);
  });

  it('drops tiles behind a moving focus, keeping a one-ring margin, and never exceeds maxTiles', () => {
    const { ctx, removed } = fakeContext();
    const s = new TileStreamer(GRID, { viewTiles: 1, maxTiles: 12, buildsPerTick: 50 });
    for (let x = 0; x <= 200; x += 2.5) {
      s.update(ctx, [{ x, y: 0, z: 1 }]);
      expect(s.count).toBeLessThanOrEqual(12);
      expect(s.isLoadedAt(x, 1)).toBe(true);
    }
    expect(removed.length).toBeGreaterThan(40);
    expect(s.isLoadedAt(0, 1)).toBe(false);
    // One tile back (just past the view) is still there while there is room.
    expect(s.isLoadedAt(200 - 15, 1)).toBe(true);
    expect(s.totals.loaded - s.totals.dropped).toBe(s.count);
  });

  it('has no tiles beyond the terrain disc', () => {
    const { ctx } = fakeContext();
    const s = new TileStreamer({ ...GRID, terrainRadiusMetres: 12 }, { viewTiles: 3, maxTiles: 100, buildsPerTick: 100 });
    s.update(ctx, [{ x: 0, y: 0, z: 0 }]);
    expect(s.inTerrain(1, 0)).toBe(true);
    expect(s.inTerrain(2, 0)).toBe(false);
    expect(s.inTerrain(-2, 0)).toBe(true); // spans [-20, -10]: its near edge is 10 m out
    expect(s.inTerrain(1, 1)).toBe(false); // its near corner (10, 10) is 14 m out
    // The 4 × 4 tiles reaching within 12 m, less the four corners.
    expect(s.count).toBe(12);
  });

  it('restores its saved state and rejects a truncated one', () => {
    const { ctx } = fakeContext();
    const s = new TileStreamer(GRID, { viewTiles: 1, maxTiles: 20, buildsPerTick: 20 });
    s.update(ctx, [{ x: 1, y: 0, z: 1 }]);
    const saved = s.save();
    s.update(ctx, [{ x: 80, y: 0, z: 1 }]);
    expect(s.save()).not.toEqual(saved);
    expect(s.restore([7, ...saved], 1)).toBe(saved.length + 1);
    expect(s.save()).toEqual(saved);
    expect(() => s.restore(saved.slice(0, 5), 0)).toThrow(/bad saved tile state/);
  });
});
