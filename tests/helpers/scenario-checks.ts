// Shared assertions for scenario tests: parameter validation and same-seed / different-seed determinism runs.
// Each helper builds fresh harnesses, so a failure names the scenario and the seed that broke it.
import { expect } from 'vitest';
import type { ScenarioDefinition } from '../../shared/sim/scenario.ts';
import { ScenarioHarness, type HarnessOptions } from './scenario-harness.ts';

/** Builds, runs `ticks` ticks (calling `drive` before each), and returns the final body states and event log. */
export async function runScenario(
  def: ScenarioDefinition,
  opts: HarnessOptions,
  ticks: number,
  drive?: (h: ScenarioHarness, tick: number) => void,
): Promise<{ ids: number[]; states: number[]; events: string }> {
  const h = await ScenarioHarness.create(def, opts);
  try {
    drive?.(h, -1);
    for (let t = 0; t < ticks; t++) {
      drive?.(h, t);
      h.step();
    }
    const snap = h.snapshot();
    return { ...snap, events: JSON.stringify(h.events) };
  } finally {
    h.destroy();
  }
}

/** Expects unknown names, out-of-range values and non-integers (where integer) to be rejected with clear Errors. */
export async function expectParamsValidated(def: ScenarioDefinition): Promise<void> {
  await expect(ScenarioHarness.create(def, { params: { noSuchParam: 1 } })).rejects.toThrow(/unknown parameter "noSuchParam" \(known: /);
  for (const [name, spec] of Object.entries(def.params)) {
    await expect(ScenarioHarness.create(def, { params: { [name]: spec.max + 1 } })).rejects.toThrow(new RegExp(`parameter ${name} must be in \\[`));
    await expect(ScenarioHarness.create(def, { params: { [name]: spec.min - 1 } })).rejects.toThrow(new RegExp(`parameter ${name} must be in \\[`));
    await expect(ScenarioHarness.create(def, { params: { [name]: Number.NaN } })).rejects.toThrow(new RegExp(`parameter ${name} must be a finite number`));
    if (spec.integer) {
      await expect(ScenarioHarness.create(def, { params: { [name]: spec.min + 0.5 } })).rejects.toThrow(new RegExp(`parameter ${name} must be an integer`));
    }
  }
}

/** Expects two builds with one seed to match bit for bit after `ticks`, and a different seed to differ. */
export async function expectSeedDeterminism(def: ScenarioDefinition, params: Record<string, number>, ticks: number, drive?: (h: ScenarioHarness, tick: number) => void): Promise<void> {
  const a = await runScenario(def, { params, seed: 7 }, ticks, drive);
  const b = await runScenario(def, { params, seed: 7 }, ticks, drive);
  const c = await runScenario(def, { params, seed: 8 }, ticks, drive);
  expect(a.ids.length).toBeGreaterThan(0);
  expect(b.ids).toEqual(a.ids);
  expect(Buffer.from(new Float32Array(b.states).buffer).equals(Buffer.from(new Float32Array(a.states).buffer))).toBe(true);
  expect(b.events).toBe(a.events);
  const same = c.ids.length === a.ids.length && c.states.every((v, i) => Object.is(v, a.states[i]));
  expect(same).toBe(false);
}
