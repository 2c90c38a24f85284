// Tests of QuantizedFrame building and its float view: which bodies a snapshot carries, at-rest flags, character
// ordering, input checks, and dequantized values close to the originals.
import { describe, expect, it } from 'vitest';
import { BodyFlag } from '../../../shared/physics-data/body-state.ts';
import { createSnapshotFormat } from '../../../shared/protocol/quantization.ts';
import { BODY_Q_STRIDE, dequantizeFrame, framesEqual, quantizeFrame } from '../../../shared/protocol/snapshot-frame.ts';
import type { CharacterState } from '../../../shared/sim/types.ts';
import { SYNTH_BOUNDS, SyntheticWorld } from './synthetic-world.ts';

const format = createSnapshotFormat(SYNTH_BOUNDS);

function character(playerId: number, x: number): CharacterState {
  return { playerId, bodyId: 50 + playerId, position: { x, y: 1, z: -2 }, velocity: { x: 1.5, y: -9, z: 0 }, yaw: 1, pitch: -0.25, groundState: 'air', buttons: 5 };
}

describe('snapshot-frame', () => {
  it('carries every non-static body and skips static ones unless asked', () => {
    const ids = new Uint32Array([1, 2, 3, 4]);
    const states = new Float32Array(4 * 13);
    for (let i = 0; i < 4; i++) states[i * 13 + 6] = 1;
    const flags = new Uint8Array([BodyFlag.Static, BodyFlag.Dynamic | BodyFlag.Active, BodyFlag.Kinematic, BodyFlag.Dynamic | BodyFlag.Character | BodyFlag.Active]);
    const read = { count: 4, ids, states, flags };
    const f = quantizeFrame(format, 10, read, []);
    expect(Array.from(f.bodyIds)).toEqual([2, 3, 4]);
    // Kinematic without Active is at rest; the active ones are not.
    expect([f.bodies[7], f.bodies[BODY_Q_STRIDE + 7], f.bodies[2 * BODY_Q_STRIDE + 7]]).toEqual([0, 1, 0]);
    const withStatic = quantizeFrame(format, 10, read, [], { includeStatic: (id) => id === 1 });
    expect(Array.from(withStatic.bodyIds)).toEqual([1, 2, 3, 4]);
  });

  it('orders characters by player id and dequantizes them close to their state', () => {
    const f = quantizeFrame(format, 3, { count: 0, ids: [], states: [], flags: [] }, [character(9, 4), character(2, -3)]);
    expect(Array.from(f.playerIds)).toEqual([2, 9]);
    const view = dequantizeFrame(format, f);
    const c = view.characters[0];
    expect(c.playerId).toBe(2);
    expect(c.bodyId).toBe(52);
    expect(c.position.x).toBeCloseTo(-3, 2);
    expect(c.velocity.y).toBeCloseTo(-9, 2);
    expect(c.yaw).toBeCloseTo(1, 3);
    expect(c.pitch).toBeCloseTo(-0.25, 3);
    expect(c.groundState).toBe('air');
    expect(c.buttons).toBe(5);
  });

  it('rejects unsorted body ids, duplicate players and bad ticks with clear errors', () => {
    const bad = { count: 2, ids: [5, 3], states: new Float32Array(26), flags: [BodyFlag.Dynamic, BodyFlag.Dynamic] };
    expect(() => quantizeFrame(format, 1, bad, [])).toThrow(/ascending/);
    expect(() => quantizeFrame(format, 1, { count: 0, ids: [], states: [], flags: [] }, [character(1, 0), character(1, 1)])).toThrow(/twice/);
    expect(() => quantizeFrame(format, -1, { count: 0, ids: [], states: [], flags: [] }, [])).toThrow(/tick/);
  });

  it('gives a float view within a millimetre and a quarter degree of the world', () => {
    const world = new SyntheticWorld({ seed: 4, bodies: 300 });
    for (let i = 0; i < 10; i++) world.step();
    const read = world.read();
    const view = dequantizeFrame(format, quantizeFrame(format, world.tick, read, world.characterStates()));
    expect(view.ids.length).toBe(read.count - 1);
    for (let i = 0; i < view.ids.length; i++) {
      for (let k = 0; k < 3; k++) expect(Math.abs(view.positions[i * 3 + k] - read.states[i * 13 + k])).toBeLessThanOrEqual(0.00101);
      let dot = 0;
      for (let k = 0; k < 4; k++) dot += view.rotations[i * 4 + k] * read.states[i * 13 + 3 + k];
      expect(Math.abs(dot)).toBeGreaterThan(Math.cos((0.25 * Math.PI) / 360));
    }
  });

  it('quantizes the same integers when it reuses the previous frame for bodies that did not move', () => {
    const world = new SyntheticWorld({ seed: 31, bodies: 40, spawnChance: 0.3, removeChance: 0.3 });
    let previous: { read: ReturnType<SyntheticWorld['read']>; frame: ReturnType<typeof quantizeFrame> } | undefined;
    let unchanged = 0;
    for (let t = 0; t < 80; t++) {
      world.step();
      const read = world.read();
      const includeStatic = t % 3 === 0 ? () => true : undefined;
      const fresh = quantizeFrame(format, world.tick, read, world.characterStates(), { includeStatic });
      const reused = quantizeFrame(format, world.tick, read, world.characterStates(), { includeStatic, previous });
      expect(framesEqual(reused, fresh)).toBe(true);
      if (previous) unchanged += fresh.bodyIds.filter((id) => previous!.frame.bodyIds.includes(id)).length;
      previous = { read, frame: reused };
    }
    expect(unchanged).toBeGreaterThan(0);
  });

  it('compares frames integer by integer', () => {
    const world = new SyntheticWorld({ seed: 8 });
    const a = quantizeFrame(format, 1, world.read(), world.characterStates());
    const b = quantizeFrame(format, 1, world.read(), world.characterStates());
    expect(framesEqual(a, b)).toBe(true);
    b.bodies[5]++;
    expect(framesEqual(a, b)).toBe(false);
  });
});
