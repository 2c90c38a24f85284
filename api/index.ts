// The package's main entry (`taos-physics`): serve your own game. createServer, defineScenario and the types a
// scenario module is written against. Node only; browsers import `taos-physics/client`.
export { createServer, type CreateServerOptions, type ScenarioEntry } from '../server/create-server.ts';
export { loadScenarioModule as loadScenario, ScenarioModuleError } from '../server/scenario-module.ts';
export type { RunningServer } from '../server/start-server.ts';
export { DEFAULT_SCENARIO, getScenario as builtInScenario, scenarioNames as builtInScenarioNames } from '../scenarios/index.ts';
export * from './scenario-kit.ts';
