// defineScenario: the public way to write a scenario. Checks a definition once, up front (each mistake a clear Error
// naming the field), fills the optional parts, freezes it and brands it so a loader can tell a scenario module's
// export from anything else. Pure: runs in Node and browsers alike.
import { resolveGameInputFields } from './game-input.ts';
import { resolveGameMessageKinds } from './game-messages.ts';
import { resolveGameStateFields } from './game-state.ts';
import { resolvePlayerRules } from './players.ts';
import { resolveParams, type ParamSpec, type ScenarioDefinition } from './scenario.ts';

/** What defineScenario takes: a ScenarioDefinition whose `params` and `golden` may be left out. */
export type ScenarioInput = Omit<ScenarioDefinition, 'params' | 'golden'> & Partial<Pick<ScenarioDefinition, 'params' | 'golden'>>;

/** A definition made by defineScenario (frozen; carries the brand loaders look for). */
export type DefinedScenario = ScenarioDefinition & { readonly [SCENARIO_BRAND]: ScenarioOrigin };

/** Where a defined scenario came from, as far as its call site shows. */
export interface ScenarioOrigin {
  /** URL (file:, http:) of the module that called defineScenario, when the call stack names it. */
  readonly sourceUrl: string | null;
}

/** The golden run a scenario gets when it declares none: ten seconds with two scripted bots. */
export const DEFAULT_GOLDEN = Object.freeze({ ticks: 600, bots: 2 });

/** Brand key, shared by every copy of this module (Symbol.for), so a scenario made by another copy is recognised. */
export const SCENARIO_BRAND: unique symbol = Symbol.for('taos-physics.defineScenario');

const NAME_PATTERN = /^[a-z0-9][a-z0-9._-]{0,63}$/;

function fail(name: string, message: string): never {
  throw new Error(`defineScenario(${name}): ${message}`);
}

function finite(v: unknown): v is number {
  return typeof v === 'number' && Number.isFinite(v);
}

function checkParamSpec(scenario: string, key: string, spec: ParamSpec): ParamSpec {
  if (spec === null || typeof spec !== 'object') fail(scenario, `params.${key} must be {default, min, max, description}`);
  if (!finite(spec.default) || !finite(spec.min) || !finite(spec.max)) fail(scenario, `params.${key}: default, min and max must be finite numbers`);
  if (spec.min > spec.max) fail(scenario, `params.${key}: min ${spec.min} is above max ${spec.max}`);
  if (typeof spec.description !== 'string') fail(scenario, `params.${key}.description must be a string`);
  return Object.freeze({ ...spec });
}

function checkVec(scenario: string, field: string, v: unknown): void {
  const p = v as { x?: unknown; y?: unknown; z?: unknown } | null;
  if (p === null || typeof p !== 'object' || !finite(p.x) || !finite(p.y) || !finite(p.z)) fail(scenario, `${field} must be {x, y, z} of finite numbers`);
}

/** The URL of the module that called defineScenario, read from the call stack (null where the stack says nothing). */
function callerUrl(): string | null {
  const stack = new Error().stack;
  if (typeof stack !== 'string') return null;
  const self = import.meta.url;
  for (const line of stack.split('\n').slice(1)) {
    // V8 names an ES module by URL; some hosts (test runners) by absolute path.
    const m = /((?:file|https?):\/\/[^\s()]+?|\/[^\s():]+)(?::\d+){1,2}\)?\s*$/.exec(line);
    if (!m) continue;
    const url = m[1].startsWith('/') ? `file://${encodeURI(m[1])}` : m[1];
    if (url !== self) return url;
  }
  return null;
}

/**
 * Checks and freezes a scenario: name (lower-case letters, digits, `.`, `_`, `-`; at most 64), description,
 * parameters (defaults inside their limits), bounds, player rules, golden run, game input, state and messages, and
 * `build`. Throws a clear Error on the first mistake. The result is what a scenario module exports (`export const scenario = defineScenario({...})`).
 */
export function defineScenario<T extends ScenarioInput>(input: T): DefinedScenario & Omit<T, 'params' | 'golden'> {
  if (input === null || typeof input !== 'object') throw new Error('defineScenario: expects an object {name, description, bounds, build, …}');
  const name = typeof input.name === 'string' ? input.name : '?';
  if (!NAME_PATTERN.test(name)) fail(name, 'name must be 1-64 characters of a-z, 0-9, ".", "_" or "-", starting with a letter or digit');
  if (typeof input.description !== 'string') fail(name, 'description must be a string');
  if (typeof input.build !== 'function') fail(name, 'build must be a function (ctx) => ScenarioInstance');
  if (input.bounds === null || typeof input.bounds !== 'object') fail(name, 'bounds must be {min, max}');
  checkVec(name, 'bounds.min', input.bounds.min);
  checkVec(name, 'bounds.max', input.bounds.max);
  const { min, max } = input.bounds;
  if (min.x >= max.x || min.y >= max.y || min.z >= max.z) fail(name, 'bounds.min must be below bounds.max on every axis');
  const params: Record<string, ParamSpec> = {};
  const givenParams = input.params ?? {};
  if (givenParams === null || typeof givenParams !== 'object') fail(name, 'params must be an object of {default, min, max, description}');
  for (const key of Object.keys(givenParams)) params[key] = checkParamSpec(name, key, givenParams[key]);
  const golden = input.golden ?? DEFAULT_GOLDEN;
  if (!Number.isInteger(golden.ticks) || golden.ticks < 0 || !Number.isInteger(golden.bots) || golden.bots < 0) fail(name, 'golden must be {ticks, bots} of integers ≥ 0');
  if (input.tickCostMs !== undefined && !(finite(input.tickCostMs) && input.tickCostMs > 0)) fail(name, 'tickCostMs must be a positive number of milliseconds');
  const def = {
    ...input,
    params: Object.freeze(params),
    bounds: Object.freeze({ min: Object.freeze({ ...min }), max: Object.freeze({ ...max }) }),
    golden: Object.freeze({ ticks: golden.ticks, bots: golden.bots }),
  };
  // Not enumerable: a spread copy ({ ...def }) is a plain definition again, not this module's scenario.
  Object.defineProperty(def, SCENARIO_BRAND, { value: Object.freeze({ sourceUrl: callerUrl() }), enumerable: false });
  // Defaults must satisfy their own limits, and the player rules must resolve: the same checks Simulation makes.
  try {
    resolveParams(def);
    resolvePlayerRules(def.players, `scenario ${name}`);
    resolveGameInputFields(def.input, name);
    resolveGameStateFields(def.state, name);
    resolveGameMessageKinds(def.messages, name);
  } catch (err) {
    fail(name, (err as Error).message);
  }
  return Object.freeze(def) as typeof def & DefinedScenario;
}

/** Whether `value` is a scenario made by defineScenario (by any copy of this package). */
export function isDefinedScenario(value: unknown): value is DefinedScenario {
  return value !== null && typeof value === 'object' && SCENARIO_BRAND in value && typeof (value as { build?: unknown }).build === 'function';
}

/** The module URL recorded when `def` was defined, or null (built-ins, stacks that name no file). */
export function scenarioSourceUrl(def: ScenarioDefinition): string | null {
  return isDefinedScenario(def) ? def[SCENARIO_BRAND].sourceUrl : null;
}
