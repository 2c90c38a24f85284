// Tests for scenarios/index.ts: the registry lists every built-in scenario sorted by name, finds them by name,
// names the known ones when a lookup fails, and every definition is well formed (defaults within limits, bounds).
import { describe, expect, it } from 'vitest';
import { DEFAULT_SCENARIO, getScenario, listScenarios, scenarioNames } from '../../scenarios/index.ts';
import { resolveParams } from '../../shared/sim/scenario.ts';

const EXPECTED = ['character-course', 'convex-hulls', 'crowd-arena', 'cubes-901', 'height-field', 'mesh-terrain', 'pendulum-chain', 'shape-rain', 'terrain-balls'];

describe('scenarios/index', () => {
  it('lists every built-in scenario, sorted by name', () => {
    expect(listScenarios().map((s) => s.name)).toEqual(EXPECTED);
    expect(scenarioNames()).toEqual(EXPECTED);
  });

  it('finds each scenario by name and serves character-course by default', () => {
    for (const name of EXPECTED) expect(getScenario(name).name).toBe(name);
    expect(DEFAULT_SCENARIO).toBe('character-course');
    expect(getScenario(DEFAULT_SCENARIO)).toBe(listScenarios()[0]);
  });

  it('throws a clear Error listing the known names for an unknown scenario', () => {
    expect(() => getScenario('shape-storm')).toThrow(`unknown scenario "shape-storm" (known: ${EXPECTED.join(', ')})`);
    expect(() => getScenario(42 as unknown as string)).toThrow(/must be a string/);
  });

  it('declares well-formed definitions: descriptions, defaults within limits, bounds, golden runs', () => {
    for (const def of listScenarios()) {
      expect(def.description.length, def.name).toBeGreaterThan(20);
      for (const [key, spec] of Object.entries(def.params)) {
        expect(spec.min, `${def.name}.${key}`).toBeLessThanOrEqual(spec.default);
        expect(spec.default, `${def.name}.${key}`).toBeLessThanOrEqual(spec.max);
        if (spec.integer) expect(Number.isInteger(spec.default) && Number.isInteger(spec.min) && Number.isInteger(spec.max), `${def.name}.${key}`).toBe(true);
        expect(spec.description.length, `${def.name}.${key}`).toBeGreaterThan(5);
      }
      expect(Object.keys(resolveParams(def))).toEqual(Object.keys(def.params));
      for (const axis of ['x', 'y', 'z'] as const) expect(def.bounds.min[axis], def.name).toBeLessThan(def.bounds.max[axis]);
      expect(Number.isInteger(def.golden.ticks) && def.golden.ticks > 0, def.name).toBe(true);
      expect(Number.isInteger(def.golden.bots) && def.golden.bots >= 0, def.name).toBe(true);
    }
  });
});
