// The scenario registry: every built-in scenario by name, the default a newcomer sees first, and lookups that
// fail with a clear Error naming the known scenarios.
import type { ScenarioDefinition } from '../shared/sim/scenario.ts';
import { scenario as characterCourse } from './character-course.ts';
import { scenario as convexHulls } from './convex-hulls.ts';
import { scenario as crowdArena } from './crowd-arena.ts';
import { scenario as cubes901 } from './cubes-901.ts';
import { scenario as heightField } from './height-field.ts';
import { scenario as meshTerrain } from './mesh-terrain.ts';
import { scenario as pendulumChain } from './pendulum-chain.ts';
import { scenario as shapeRain } from './shape-rain.ts';
import { scenario as terrainBalls } from './terrain-balls.ts';

/** The scenario served when none is named. */
export const DEFAULT_SCENARIO = 'character-course';

const ALL: readonly ScenarioDefinition[] = Object.freeze(
  [characterCourse, convexHulls, crowdArena, cubes901, heightField, meshTerrain, pendulumChain, shapeRain, terrainBalls].sort((a, b) => (a.name < b.name ? -1 : a.name > b.name ? 1 : 0)),
);
const BY_NAME = new Map(ALL.map((s) => [s.name, s]));

/** Every built-in scenario, sorted by name. */
export function listScenarios(): readonly ScenarioDefinition[] {
  return ALL;
}

/** Names of every built-in scenario, sorted. */
export function scenarioNames(): string[] {
  return ALL.map((s) => s.name);
}

/** The scenario called `name`; throws an Error listing the known names when there is none. */
export function getScenario(name: string): ScenarioDefinition {
  if (typeof name !== 'string') throw new Error(`getScenario: a scenario name must be a string, got ${typeof name}`);
  const def = BY_NAME.get(name);
  if (!def) throw new Error(`unknown scenario "${name}" (known: ${scenarioNames().join(', ')})`);
  return def;
}
