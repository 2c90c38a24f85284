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

/**
 * Expects every dynamic scenario body to sit on the static surface below it (within `maxGapMetres`), at least 85% of
 * them slower than `restSpeed` (m/s) and none faster than 8× that (a ball may still be rocking in a hollow).
 */
export function expectRestingOnSurface(h: ScenarioHarness, maxGapMetres: number, restSpeed: number): void {
  const bodies = h.dynamicBodies();
  expect(bodies.length).toBeGreaterThan(0);
  const speeds: number[] = [];
  for (const b of bodies) {
    const p = b.position();
    const ground = h.world.rayDownY(p.x, p.y, p.z, 50, true);
    expect(ground, `body ${b.id} has terrain below it`).not.toBeNull();
    expect(p.y - ground!, `body ${b.id} above the surface`).toBeGreaterThan(0);
    expect(p.y - ground!, `body ${b.id} close to the surface`).toBeLessThan(maxGapMetres);
    const v = b.linearVelocity();
    speeds.push(Math.sqrt(v.x * v.x + v.y * v.y + v.z * v.z));
  }
  expect(Math.max(...speeds)).toBeLessThan(8 * restSpeed);
  expect(speeds.filter((s) => s < restSpeed).length).toBeGreaterThanOrEqual(0.85 * bodies.length);
}
