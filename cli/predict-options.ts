// Predicted play for Node clients (bots, tests, benches): the client library's predict option with a local
// Simulation of the scenario the room runs (a built-in, or one of the scenarios given).
import '../server/physics-node.ts';
import type { PredictOptions } from '../sdk/index.ts';
import type { ScenarioDefinition } from '../shared/sim/scenario.ts';
import { createSimulation, scenarioNamed } from './scenario-setup.ts';

/**
 * connect()'s predict option for Node: simulations of `scenarios` (your own, e.g. a game module) or the built-ins;
 * `extra` tunes budgets and smoothing.
 */
export function nodePredictOptions(extra: Omit<PredictOptions, 'createSimulation'> = {}, scenarios: readonly ScenarioDefinition[] = []): PredictOptions {
  const named = (name: string): ScenarioDefinition => scenarios.find((s) => s.name === name) ?? scenarioNamed(name);
  return { ...extra, createSimulation: (setup) => createSimulation(named(setup.scenario), setup.params, setup.seed) };
}
