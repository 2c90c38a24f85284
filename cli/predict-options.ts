// Predicted play for Node clients (bots, tests, benches): the client library's predict option with a local
// Simulation of the built-in scenario the room runs.
import '../server/physics-node.ts';
import type { PredictOptions } from '../sdk/index.ts';
import { createSimulation, scenarioNamed } from './scenario-setup.ts';

/** connect()'s predict option for Node: simulations of built-in scenarios; `extra` tunes budgets and smoothing. */
export function nodePredictOptions(extra: Omit<PredictOptions, 'createSimulation'> = {}): PredictOptions {
  return { ...extra, createSimulation: (setup) => createSimulation(scenarioNamed(setup.scenario), setup.params, setup.seed) };
}
