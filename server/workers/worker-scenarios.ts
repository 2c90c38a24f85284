// The scenarios a room worker can open: the built-in registry plus every ScenarioDefinition exported by the modules
// the server names (a test's own scenes). A worker cannot be handed definitions: they hold functions.
import { listScenarios } from '../../scenarios/index.ts';
import type { ScenarioDefinition } from '../../shared/sim/scenario.ts';
import type { ScenarioSource } from '../room-factory.ts';

function isScenario(value: unknown): value is ScenarioDefinition {
  if (typeof value !== 'object' || value === null) return false;
  const v = value as Partial<ScenarioDefinition>;
  return typeof v.name === 'string' && typeof v.build === 'function' && typeof v.params === 'object';
}

/** The registry and the exported scenarios of `modules` (file URLs); a later module's name wins. */
export async function loadScenarioSource(modules: readonly string[]): Promise<ScenarioSource> {
  const byName = new Map<string, ScenarioDefinition>();
  for (const s of listScenarios()) byName.set(s.name, s);
  for (const url of modules) {
    const mod = (await import(url)) as Record<string, unknown>;
    for (const value of Object.values(mod)) if (isScenario(value)) byName.set(value.name, value);
  }
  return { get: (name) => byName.get(name), names: () => [...byName.keys()] };
}
