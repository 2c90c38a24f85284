// Tests of the net-mode policy: every built-in scenario predicts at default parameters, a scene too costly to roll
// back in a frame stays on snapshots and says why, an explicit snapshot request wins, and an unknown scenario
// predicts only when asked by name.
import { describe, expect, it } from 'vitest';
import { listScenarios } from '../../scenarios/index.ts';
import { resolveParams } from '../../shared/sim/scenario.ts';
import { decideNetMode, EXPECTED_ROLLBACK_TICKS, isNetModeRequest } from '../../server/net-mode-policy.ts';

describe('net-mode-policy', () => {
  it('predicts every built-in scenario at its default parameters', () => {
    for (const def of listScenarios()) {
      const d = decideNetMode('auto', def.name, resolveParams(def, {}));
      expect(d.mode, def.name).toBe('predict');
      expect(d.affordableRollbackTicks, def.name).toBeGreaterThanOrEqual(EXPECTED_ROLLBACK_TICKS);
    }
  });

  it('keeps shape-rain with 1000 bodies on snapshots and says why', () => {
    const def = listScenarios().find((s) => s.name === 'shape-rain')!;
    for (const request of ['auto', 'predict'] as const) {
      const d = decideNetMode(request, def.name, resolveParams(def, { count: 1000 }));
      expect(d.mode).toBe('snapshot');
      expect(d.affordableRollbackTicks).toBe(2);
      expect(d.note).toMatch(/affords 2 ticks of rollback, fewer than the 6/);
    }
  });

  it('serves snapshots when asked and predicts an unknown scenario only when asked by name', () => {
    expect(decideNetMode('snapshot', 'cubes-901', {}).mode).toBe('snapshot');
    expect(decideNetMode('predict', 'test-arena', {})).toEqual({ mode: 'predict', affordableRollbackTicks: null, note: null });
    expect(decideNetMode('auto', 'test-arena', {}).mode).toBe('snapshot');
    expect(isNetModeRequest('auto')).toBe(true);
    expect(isNetModeRequest('lockstep')).toBe(false);
  });

  it('predicts a scenario outside the built-ins on auto when its own tickCostMs fits the frame, and says why not when it does not', () => {
    expect(decideNetMode('auto', 'ball-goals', {}, 0.2)).toEqual({ mode: 'predict', affordableRollbackTicks: 83, note: null });
    const heavy = decideNetMode('auto', 'ball-goals', {}, 5);
    expect(heavy.mode).toBe('snapshot');
    expect(heavy.note).toMatch(/affords 3 ticks of rollback/);
    expect(decideNetMode('auto', 'ball-goals', {}).note).toMatch(/gives no tickCostMs/);
  });
});
