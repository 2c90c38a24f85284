// Tests for the bench's floor: a floor batch times each present character's update and the world step, and leaves
// the simulation exactly where it was, so the full tick that follows runs the very same ticks.
import { describe, expect, it } from 'vitest';
import { floorStepBatch, rawStepBatch } from '../../../bench/lib/raw-step.ts';
import { botRecords, createSceneSim } from '../../../bench/lib/scenes.ts';

const SCENE = { scenario: 'shape-rain', params: { count: 40 }, label: 'shape-rain 40' };

describe('raw-step', () => {
  it('leaves the simulation where it was: the next ticks hash as in a twin that never ran a floor batch', async () => {
    const sim = await createSceneSim(SCENE);
    const twin = await createSceneSim(SCENE);
    try {
      const bots = botRecords(3);
      const twinBots = botRecords(3);
      for (let t = 0; t < 40; t++) {
        sim.step(bots.next());
        twin.step(twinBots.next());
      }
      const before = sim.stateHash();
      const floor = floorStepBatch(sim, 6);
      expect(sim.stateHash()).toBe(before);
      expect(rawStepBatch(sim, 3)).toHaveLength(3);
      for (let t = 0; t < 20; t++) {
        sim.step(bots.next());
        twin.step(twinBots.next());
      }
      expect(sim.stateHash()).toBe(twin.stateHash());
      expect(floor).toHaveLength(6);
      for (const tick of floor) {
        expect(tick.characterMs).toBeGreaterThan(0);
        expect(tick.ms).toBeGreaterThan(tick.characterMs);
      }
    } finally {
      sim.destroy();
      twin.destroy();
    }
  });

  it('has no character part in a scene without players, and refuses a batch that is not a positive tick count', async () => {
    const sim = await createSceneSim(SCENE);
    try {
      expect(floorStepBatch(sim, 2).map((t) => t.characterMs)).toEqual([0, 0]);
      expect(() => floorStepBatch(sim, 0)).toThrow(/positive integer/);
      expect(() => rawStepBatch(sim, 1.5)).toThrow(/positive integer/);
    } finally {
      sim.destroy();
    }
  });
});
