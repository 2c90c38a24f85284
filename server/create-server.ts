// createServer: the package's way to serve your own game in code. Takes the scenarios to offer (defineScenario
// results, module paths, or built-in names), checks them, and starts the server (start-server.ts) on them.
import { resolve } from 'node:path';
import { pathToFileURL } from 'node:url';
import { getScenario, listScenarios } from '../scenarios/index.ts';
import { scenarioSourceUrl } from '../shared/sim/define-scenario.ts';
import type { ScenarioDefinition } from '../shared/sim/scenario.ts';
import type { ScenarioSource } from './room-factory.ts';
import { isScenarioPath, loadScenarioModule } from './scenario-module.ts';
import { startServer, type RunningServer, type StartServerOptions } from './start-server.ts';

/** One scenario to offer: a definition, a module file to load (`./game.ts`), or a built-in scenario's name. */
export type ScenarioEntry = ScenarioDefinition | string;

/** Options of createServer: startServer's, with scenarios given as a list. */
export interface CreateServerOptions extends Omit<StartServerOptions, 'scenarios' | 'scenario'> {
  /** The scenarios rooms may run; default every built-in one. */
  scenarios?: readonly ScenarioEntry[];
  /** The default room's scenario; default the first of `scenarios` (or character-course without them). */
  scenario?: string;
}

/** A fixed list of scenarios as a ScenarioSource; two with one name are an Error. */
export function scenarioSource(defs: readonly ScenarioDefinition[]): ScenarioSource {
  const byName = new Map<string, ScenarioDefinition>();
  for (const def of defs) {
    if (def === null || typeof def !== 'object' || typeof def.name !== 'string') throw new Error('scenarios: every entry must be a scenario definition (defineScenario(...))');
    if (byName.has(def.name)) throw new Error(`scenarios: two scenarios are called "${def.name}"`);
    byName.set(def.name, def);
  }
  return { get: (name) => byName.get(name), names: () => [...byName.keys()] };
}

/** Turns entries into definitions: module paths are loaded, names looked up among the built-in scenarios. */
export async function resolveScenarioEntries(entries: readonly ScenarioEntry[]): Promise<ScenarioDefinition[]> {
  const out: ScenarioDefinition[] = [];
  for (const entry of entries) {
    if (typeof entry !== 'string') out.push(entry);
    else out.push(isScenarioPath(entry) ? await loadScenarioModule(entry) : getScenario(entry));
  }
  return out;
}

/** Starts a server offering `opts.scenarios` (listening on `opts.port`, default 8080; 0 picks a free port). */
export async function createServer(opts: CreateServerOptions = {}): Promise<RunningServer> {
  const { scenarios: entries, ...rest } = opts;
  if (entries !== undefined && (!Array.isArray(entries) || entries.length === 0)) throw new Error('createServer: scenarios must be a non-empty array');
  const defs = entries === undefined ? [...listScenarios()] : await resolveScenarioEntries(entries);
  const source = scenarioSource(defs);
  // Rooms in worker threads import the scenarios' modules themselves (a definition holds functions, which cannot
  // cross to a thread): module paths as given, definitions through the module that called defineScenario.
  const modules: string[] = [];
  for (const entry of entries ?? []) {
    if (typeof entry === 'string') {
      if (isScenarioPath(entry)) modules.push(pathToFileURL(resolve(entry)).href);
      continue;
    }
    const url = scenarioSourceUrl(entry);
    if (url !== null && url.startsWith('file:')) modules.push(url);
    else if ((rest.roomWorkers ?? 0) > 0) {
      throw new Error(`createServer: rooms in worker threads load scenarios from module files, and the module of scenario "${entry.name}" is unknown (make it with defineScenario in a module file, give its path, or set roomWorkers: 0)`);
    }
  }
  return startServer({ ...rest, workerScenarioModules: [...(rest.workerScenarioModules ?? []), ...modules], scenarios: source, scenario: opts.scenario ?? (entries === undefined ? undefined : defs[0].name) });
}
