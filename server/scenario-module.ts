// A game's own scenario, loaded from its module file (`--scenario ./game.ts`), and the content hash of that module
// that input logs store so a replay can tell whether it runs the same version of the game. Node only.
import { createHash } from 'node:crypto';
import { readFile, stat } from 'node:fs/promises';
import { dirname, resolve } from 'node:path';
import { fileURLToPath, pathToFileURL } from 'node:url';
import { isDefinedScenario, scenarioSourceUrl } from '../shared/sim/define-scenario.ts';
import type { ScenarioDefinition } from '../shared/sim/scenario.ts';

/** A module file could not be loaded as a scenario (missing, failing, or exporting no defineScenario result). */
export class ScenarioModuleError extends Error {
  override name = 'ScenarioModuleError';
}

/** Module hashes by definition: set when a module is loaded, or computed once from the definition's source URL. */
const hashes = new WeakMap<ScenarioDefinition, Promise<string>>();

/** Whether a --scenario value names a module file rather than a built-in scenario. */
export function isScenarioPath(value: string): boolean {
  return value.includes('/') || value.includes('\\') || /\.(?:[cm]?[jt]s)$/.test(value);
}

/**
 * The content hash of a module and every local file it imports (packages excluded), as `sha256:<hex>`: the same
 * source files give the same hash on any machine, and an edit to any of them changes it.
 */
export async function moduleSourceHash(path: string): Promise<string> {
  const entry = resolve(path);
  const dir = dirname(entry);
  let files: string[];
  try {
    const { build } = await import('esbuild');
    const result = await build({ entryPoints: [entry], bundle: true, write: false, metafile: true, packages: 'external', platform: 'node', format: 'esm', logLevel: 'silent', absWorkingDir: dir, outdir: dir });
    files = Object.keys(result.metafile.inputs).sort();
  } catch {
    files = [entry]; // a module the bundler cannot follow (e.g. an addon import): the entry file alone
  }
  const h = createHash('sha256');
  for (const file of files) {
    const abs = resolve(dir, file);
    const rel = abs === entry ? '<entry>' : file.replace(/\\/g, '/');
    h.update(`${rel}\0`);
    h.update(await readFile(abs));
    h.update('\0');
  }
  return `sha256:${h.digest('hex')}`;
}

/**
 * Imports a scenario module and returns its definition: the export named `scenario`, else the default export; it
 * must be a defineScenario(...) result. Records the module's content hash for scenarioModuleHash.
 */
export async function loadScenarioModule(path: string): Promise<ScenarioDefinition> {
  const abs = resolve(path);
  try {
    if (!(await stat(abs)).isFile()) throw new ScenarioModuleError(`${path} is not a file`);
  } catch (err) {
    if (err instanceof ScenarioModuleError) throw err;
    throw new ScenarioModuleError(`no such scenario module: ${path}`);
  }
  let mod: Record<string, unknown>;
  try {
    mod = (await import(pathToFileURL(abs).href)) as Record<string, unknown>;
  } catch (err) {
    throw new ScenarioModuleError(`cannot load scenario module ${path}: ${err instanceof Error ? err.message : String(err)}`, { cause: err });
  }
  const def = mod.scenario ?? mod.default;
  if (!isDefinedScenario(def)) {
    const found = Object.keys(mod).join(', ') || 'nothing';
    throw new ScenarioModuleError(`${path} must export a defineScenario(...) result as "scenario" (or as its default export); it exports ${found}`);
  }
  if (!hashes.has(def)) hashes.set(def, moduleSourceHash(abs));
  await hashes.get(def);
  return def;
}

/**
 * The content hash of the module a scenario came from ('' for built-in scenarios and definitions whose module is
 * unknown). Computed once per definition.
 */
export function scenarioModuleHash(def: ScenarioDefinition): Promise<string> {
  let hash = hashes.get(def);
  if (hash === undefined) {
    const url = scenarioSourceUrl(def);
    hash = url !== null && url.startsWith('file:') ? moduleSourceHash(fileURLToPath(url)).catch(() => '') : Promise.resolve('');
    hashes.set(def, hash);
  }
  return hash;
}

/** A short form of a module hash for messages (`sha256:0123456789ab`). */
export function shortHash(hash: string): string {
  return hash === '' ? '(none)' : hash.slice(0, 'sha256:'.length + 12);
}
