// Tests of shared/sim/define-scenario.ts: a good definition comes back frozen with defaults filled and branded;
// each kind of mistake is a clear Error naming the field.
import { describe, expect, it } from 'vitest';
import { DEFAULT_GOLDEN, defineScenario, isDefinedScenario, scenarioSourceUrl, type ScenarioInput } from '../../../shared/sim/define-scenario.ts';
import { getScenario } from '../../../scenarios/index.ts';

const base: ScenarioInput = {
  name: 'my-game',
  description: 'a test scene',
  bounds: { min: { x: -10, y: -5, z: -10 }, max: { x: 10, y: 20, z: 10 } },
  build: () => ({ spawnPoint: () => ({ x: 0, y: 0, z: 0 }) }),
};

describe('defineScenario', () => {
  it('returns a frozen, branded definition with the golden run and parameters filled in', () => {
    const def = defineScenario(base);
    expect(def.name).toBe('my-game');
    expect(def.params).toEqual({});
    expect(def.golden).toEqual(DEFAULT_GOLDEN);
    expect(Object.isFrozen(def)).toBe(true);
    expect(isDefinedScenario(def)).toBe(true);
    expect(isDefinedScenario(getScenario('shape-rain'))).toBe(false);
    expect(isDefinedScenario({ ...base })).toBe(false);
    expect(isDefinedScenario({ ...def })).toBe(false);
  });

  it('records the module that called it', () => {
    expect(scenarioSourceUrl(defineScenario(base))).toBe(import.meta.url);
    expect(scenarioSourceUrl(getScenario('shape-rain'))).toBeNull();
  });

  it('keeps fields it does not know (a game may add its own)', () => {
    const def = defineScenario({ ...base, extra: 7 } as ScenarioInput & { extra: number });
    expect((def as unknown as { extra: number }).extra).toBe(7);
  });

  it('rejects a bad name, missing build, bad bounds, bad parameters, bad golden run and bad player rules', () => {
    expect(() => defineScenario({ ...base, name: 'My Game' })).toThrow(/defineScenario\(My Game\): name must be 1-64 characters/);
    expect(() => defineScenario({ ...base, name: '' })).toThrow(/name must be/);
    expect(() => defineScenario({ ...base, build: undefined as never })).toThrow(/build must be a function/);
    expect(() => defineScenario({ ...base, description: 3 as never })).toThrow(/description must be a string/);
    expect(() => defineScenario({ ...base, bounds: { min: { x: 0, y: 0, z: 0 }, max: { x: 1, y: 0, z: 1 } } })).toThrow(/bounds.min must be below bounds.max/);
    expect(() => defineScenario({ ...base, bounds: { min: { x: 0, y: Number.NaN, z: 0 }, max: { x: 1, y: 1, z: 1 } } })).toThrow(/bounds.min must be \{x, y, z\} of finite numbers/);
    expect(() => defineScenario({ ...base, params: { n: { default: 5, min: 10, max: 1, description: '' } } })).toThrow(/params.n: min 10 is above max 1/);
    expect(() => defineScenario({ ...base, params: { n: { default: 50, min: 0, max: 10, description: '' } } })).toThrow(/parameter n must be in \[0, 10\], got 50/);
    expect(() => defineScenario({ ...base, params: { n: { default: 1.5, min: 0, max: 10, integer: true, description: '' } } })).toThrow(/must be an integer/);
    expect(() => defineScenario({ ...base, golden: { ticks: -1, bots: 0 } })).toThrow(/golden must be/);
    expect(() => defineScenario({ ...base, players: { walkSpeedMetresPerSecond: -1 } })).toThrow(/players.walkSpeedMetresPerSecond/);
    expect(() => defineScenario(null as never)).toThrow(/expects an object/);
  });

  it('rejects bad game input, state and message declarations up front, naming the field', () => {
    expect(() => defineScenario({ ...base, input: { yaw: { kind: 'button' } } })).toThrow(/defineScenario\(.*\): scenario .*: input field "yaw": the name is taken/);
    expect(() => defineScenario({ ...base, state: { score: { kind: 'text' as never } } })).toThrow(/state field "score": kind must be 'number' or 'string'/);
    expect(() => defineScenario({ ...base, messages: { pick: { payload: { team: { min: 1, max: 0 } } } } })).toThrow(/message "pick": payload field team needs integer min ≤ max/);
  });
});
