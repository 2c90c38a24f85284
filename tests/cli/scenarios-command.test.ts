// Tests for `scenarios`: every registered scenario is listed with its description and parameter limits.
import { describe, expect, it } from 'vitest';
import { listScenarios } from '../../scenarios/index.ts';
import { cli } from '../helpers/cli.ts';

describe('scenarios-command', () => {
  it('lists every scenario with description, parameters, defaults and limits as JSON', async () => {
    const r = await cli('scenarios', '--json');
    expect(r.code).toBe(0);
    const list = JSON.parse(r.stdout) as Array<{ name: string; description: string; params: Record<string, { default: number; min: number; max: number; integer: boolean }> }>;
    expect(list.map((s) => s.name)).toEqual(listScenarios().map((s) => s.name));
    for (const def of listScenarios()) {
      const shown = list.find((s) => s.name === def.name)!;
      expect(shown.description).toBe(def.description);
      for (const [k, p] of Object.entries(def.params)) expect(shown.params[k]).toMatchObject({ default: p.default, min: p.min, max: p.max, integer: p.integer === true });
    }
    expect(r.stdout.trim().split('\n')).toHaveLength(1);
  });

  it('prints a readable listing with each parameter\'s default and range', async () => {
    const r = await cli('scenarios');
    expect(r.code).toBe(0);
    expect(r.stdout).toMatch(/^character-course\n  A small course/);
    expect(r.stdout).toMatch(/--param crateRows\s+default 3\s+\[0, 8\] integer/);
    const lines = r.stdout.split('\n');
    for (const def of listScenarios()) expect(lines).toContain(def.name);
  });
});
