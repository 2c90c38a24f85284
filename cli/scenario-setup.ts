// Turns command-line scenario choices into a Simulation: scenario lookup by name or module file, parameter and seed
// checks (each mistake a UsageError naming the valid choices), and Jolt loading for Node.
import '../server/physics-node.ts';
import { getScenario, listScenarios } from '../scenarios/index.ts';
import { isScenarioPath, loadScenarioModule, ScenarioModuleError } from '../server/scenario-module.ts';
import { resolveParams, type ScenarioDefinition } from '../shared/sim/scenario.ts';
import { Simulation } from '../shared/sim/simulation.ts';
import { didYouMean } from './args.ts';
import { UsageError } from './command.ts';

/** Every registered scenario, in listing order. */
export function allScenarios(): readonly ScenarioDefinition[] {
  return listScenarios();
}

/** The scenario called `name`; a UsageError lists the known ones. */
export function scenarioNamed(name: string): ScenarioDefinition {
  let def: ScenarioDefinition | undefined;
  try {
    def = getScenario(name) ?? undefined;
  } catch {
    def = undefined;
  }
  if (def) return def;
  const names = allScenarios().map((s) => s.name);
  throw new UsageError(`unknown scenario '${name}'${didYouMean(name, names)}; known: ${names.join(', ')}`);
}

/** What a --scenario value names: a module file (`./game.ts`, exporting a defineScenario result) or a built-in. */
export async function scenarioFromArg(value: string): Promise<ScenarioDefinition> {
  if (!isScenarioPath(value)) return scenarioNamed(value);
  try {
    return await loadScenarioModule(value);
  } catch (err) {
    if (err instanceof ScenarioModuleError) throw new UsageError(err.message);
    throw err;
  }
}

/** Checks parameters against the scenario's declared limits (UsageError on an unknown name or a bad value). */
export function checkParams(def: ScenarioDefinition, params: Readonly<Record<string, number>>): void {
  try {
    resolveParams(def, params);
  } catch (err) {
    throw new UsageError((err as Error).message);
  }
}

/** A --seed value: an integer in [0, 2^32) when it looks numeric, otherwise the string itself. */
export function parseSeed(raw: string | undefined, fallback: number | string = 1): number | string {
  if (raw === undefined) return fallback;
  if (raw === '') throw new UsageError('--seed must not be empty');
  if (/^[-+]?[\d.]/.test(raw)) {
    const n = Number(raw);
    if (!/^\d+$/.test(raw) || !Number.isSafeInteger(n) || n > 0xffffffff) {
      throw new UsageError(`--seed must be an integer in [0, 4294967295] or a word, got "${raw}"`);
    }
    return n;
  }
  return raw;
}

/** Creates the simulation for a checked scenario, parameters and seed. */
export async function createSimulation(def: ScenarioDefinition, params: Readonly<Record<string, number>>, seed: number | string): Promise<Simulation> {
  checkParams(def, params);
  return Simulation.create({ scenario: def, params, seed });
}
