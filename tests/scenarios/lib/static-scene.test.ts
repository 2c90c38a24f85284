// Tests for scenarios/lib/static-scene.ts: the ground's top face, walls enclosing the square, blocks filling their
// corners, and the Error for an inside-out block.
import { describe, expect, it } from 'vitest';
import { addBlock, addBoundaryWalls, addGround } from '../../../scenarios/lib/static-scene.ts';
import type { ScenarioContext, ScenarioDefinition } from '../../../shared/sim/scenario.ts';
import { ScenarioHarness } from '../../helpers/scenario-harness.ts';

/** A throwaway scenario whose build runs `body`. */
function sceneOf(body: (ctx: ScenarioContext) => void): ScenarioDefinition {
  return {
    name: 'static-scene-test',
    description: 'static scene helpers under test',
    params: {},
    bounds: { min: { x: -50, y: -10, z: -50 }, max: { x: 50, y: 50, z: 50 } },
    golden: { ticks: 1, bots: 0 },
    build(ctx) {
      body(ctx);
      return { spawnPoint: () => ({ x: 0, y: 0, z: 0 }) };
    },
  };
}

describe('static-scene', () => {
  it('rings the ground with walls that stop a rolling ball', async () => {
    const h = await ScenarioHarness.create(sceneOf((ctx) => {
      addGround(ctx, 10);
      addBoundaryWalls(ctx, 5, 1);
    }));
    try {
      expect(h.world.rayDownY(3, 5, -2, 10, true)).toBeCloseTo(0, 5);
      const ball = h.world.addSphere(0.3, { x: 0, y: 0.3, z: 0 }, { linearVelocity: { x: 8, y: 0, z: 0 } });
      h.run(120);
      expect(ball.position().x).toBeLessThan(5);
      expect(ball.position().y).toBeGreaterThan(0);
    } finally {
      h.destroy();
    }
  });

  it('puts the ground top at topY, fills a block between its corners and rejects an inside-out one', async () => {
    const h = await ScenarioHarness.create(sceneOf((ctx) => {
      addGround(ctx, 20, -2);
      addBlock(ctx, { x: 1, y: 0, z: 2 }, { x: 3, y: 0.5, z: 6 }, [1, 0, 0], 'step');
    }));
    try {
      expect(h.world.rayDownY(10, 3, 10, 10, true)).toBeCloseTo(-2, 5);
      const block = h.scenarioBodyIds().map((id) => h.world.getBody(id)!).find((b) => b.name === 'step')!;
      expect(block.name).toBe('step');
      expect(block.position()).toEqual({ x: 2, y: 0.25, z: 4 });
      expect(h.world.rayDownY(2.9, 3, 5.9, 5, true)).toBeCloseTo(0.5, 5);
    } finally {
      h.destroy();
    }
    await expect(ScenarioHarness.create(sceneOf((ctx) => addBlock(ctx, { x: 1, y: 0, z: 0 }, { x: 0, y: 1, z: 1 }, [1, 1, 1], 'bad')))).rejects.toThrow(/addBlock "bad": max must exceed min/);
  });
});
