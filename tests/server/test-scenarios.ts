// Small scenes for server tests: a ground strip with a trigger zone players walk into, and a few loose boxes that
// give snapshots something to carry. Built through the scenario contract like any real scenario.
import { CollisionLayer } from '../../shared/physics/index.ts';
import type { ScenarioDefinition } from '../../shared/sim/scenario.ts';

/** Trigger zone spans x ∈ [3, 4] across the strip; players spawn at x = 0, one per 2 m along z. */
export const TRIGGER_MIN_X = 3;

/** The strip: ground, a trigger zone, and `boxes` dynamic boxes dropped off to the side. */
export const stripScenario: ScenarioDefinition = {
  name: 'test-strip',
  description: 'Test strip: walk +x into the trigger zone.',
  params: { boxes: { default: 4, min: 0, max: 50, integer: true, description: 'loose boxes' } },
  bounds: { min: { x: -20, y: -5, z: -20 }, max: { x: 20, y: 20, z: 20 } },
  golden: { ticks: 60, bots: 1 },
  build(ctx) {
    ctx.spawn({ kind: 'box', halfExtents: { x: 15, y: 0.5, z: 15 } }, { x: 0, y: -0.5, z: 0 }, null, { motion: 'static', name: 'ground' });
    ctx.spawn({ kind: 'box', halfExtents: { x: 0.5, y: 1.5, z: 10 } }, { x: TRIGGER_MIN_X + 0.5, y: 1.5, z: 0 }, null, {
      motion: 'static',
      isSensor: true,
      layer: CollisionLayer.Trigger,
      mask: CollisionLayer.Player,
      hidden: true,
      name: 'zone',
    });
    for (let i = 0; i < ctx.params.boxes; i++) {
      ctx.spawn({ kind: 'box', halfExtents: { x: 0.25, y: 0.25, z: 0.25 } }, { x: -5, y: 0.5 + i * 0.6, z: -5 + (i % 3) * 0.05 }, null, { motion: 'dynamic', name: `box ${i}` });
    }
    return { spawnPoint: (n) => ({ x: 0, y: 0.05, z: -6 + 2 * (n % 6) }) };
  },
};

/** A second scene, for rooms created on demand. */
export const emptyScenario: ScenarioDefinition = {
  name: 'test-empty',
  description: 'Just ground.',
  params: {},
  bounds: { min: { x: -20, y: -5, z: -20 }, max: { x: 20, y: 20, z: 20 } },
  golden: { ticks: 60, bots: 1 },
  build(ctx) {
    ctx.spawn({ kind: 'box', halfExtents: { x: 15, y: 0.5, z: 15 } }, { x: 0, y: -0.5, z: 0 }, null, { motion: 'static', name: 'ground' });
    return { spawnPoint: () => ({ x: 0, y: 0.05, z: 0 }) };
  },
};

/** Ticks at which streamScenario adds, then removes, a static block (like streamed terrain tiles). */
export const STREAM_ADD_TICK = 20;
export const STREAM_REMOVE_TICK = 200;

/** Ground built up front; a static block spawned during a tick and removed later. */
export const streamScenario: ScenarioDefinition = {
  name: 'test-stream',
  description: 'A static block streams in and out.',
  params: {},
  bounds: { min: { x: -20, y: -5, z: -20 }, max: { x: 20, y: 20, z: 20 } },
  golden: { ticks: 60, bots: 1 },
  build(ctx) {
    ctx.spawn({ kind: 'box', halfExtents: { x: 15, y: 0.5, z: 15 } }, { x: 0, y: -0.5, z: 0 }, null, { motion: 'static', name: 'ground' });
    let block = 0;
    return {
      spawnPoint: () => ({ x: 0, y: 0.05, z: 0 }),
      onTick(c) {
        if (c.tick === STREAM_ADD_TICK) block = c.spawn({ kind: 'box', halfExtents: { x: 1, y: 0.5, z: 1 } }, { x: 5, y: 0.5, z: 5 }, null, { motion: 'static', name: 'tile' }).id;
        if (c.tick === STREAM_REMOVE_TICK && block) c.remove(block);
      },
      saveState: () => [block],
      restoreState: (s) => {
        block = s[0];
      },
    };
  },
};
