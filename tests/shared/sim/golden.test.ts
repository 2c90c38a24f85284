// Tests of the golden runner and golden files: a golden run is reproducible, sensitive to its seed, and golden files
// are validated field by field and written in a stable form.
import { describe, expect, it } from 'vitest';
import '../../../server/physics-node.ts';
import { formatGoldenFile, GOLDEN_SEED, parseGoldenFile, runGolden } from '../../../shared/sim/golden.ts';
import { testArena } from './helpers/test-scenarios.ts';

describe('golden', () => {
  it('reproduces the same final hash on every run and records hashes every 60 ticks', async () => {
    const a = await runGolden(testArena);
    const b = await runGolden(testArena);
    expect(a).toEqual(b);
    expect(a).toMatchObject({ scenario: 'test-arena', ticks: 120, bots: 2, seed: GOLDEN_SEED });
    expect(a.checkpoints.map((c) => c.tick)).toEqual([60, 120]);
    expect(a.checkpoints[1].hash).toBe(a.hash);
  });

  it('depends on the seed and the number of bots', async () => {
    const base = await runGolden(testArena, { ticks: 60 });
    expect((await runGolden(testArena, { ticks: 60, seed: 1 })).hash).not.toBe(base.hash);
    expect((await runGolden(testArena, { ticks: 60, bots: 0 })).hash).not.toBe(base.hash);
  });

  it('writes golden files in a stable form that parses back', async () => {
    const result = { scenario: 's', ticks: 10, bots: 1, seed: 3, hash: '0123456789abcdef', checkpoints: [] };
    const text = formatGoldenFile(result, '1.1.0');
    expect(text).toBe('{\n  "scenario": "s",\n  "ticks": 10,\n  "bots": 1,\n  "seed": 3,\n  "hash": "0123456789abcdef",\n  "joltVersion": "1.1.0"\n}\n');
    expect(parseGoldenFile(JSON.parse(text), 'f')).toEqual({ scenario: 's', ticks: 10, bots: 1, seed: 3, hash: '0123456789abcdef', joltVersion: '1.1.0' });
  });

  it('rejects malformed golden files naming the bad field', () => {
    const ok = { scenario: 's', ticks: 10, bots: 1, seed: 3, hash: '0123456789abcdef', joltVersion: '1.1.0' };
    expect(() => parseGoldenFile([], 'f.json')).toThrow(/f.json: a golden file must hold a JSON object/);
    expect(() => parseGoldenFile({ ...ok, hash: 'XYZ' }, 'f')).toThrow(/"hash" must be 16 lowercase hex/);
    expect(() => parseGoldenFile({ ...ok, ticks: -2 }, 'f')).toThrow(/"ticks" must be a non-negative integer/);
    expect(() => parseGoldenFile({ ...ok, joltVersion: '' }, 'f')).toThrow(/"joltVersion"/);
  });

  it('refuses a scenario without a usable golden script', async () => {
    await expect(runGolden({ ...testArena, golden: { ticks: 0, bots: 1 } })).rejects.toThrow(/golden.ticks must be an integer >= 1/);
  });
});
