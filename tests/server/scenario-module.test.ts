// Tests of server/scenario-module.ts: a game's module loads as its defineScenario result; anything else is a clear
// ScenarioModuleError; the module hash is the same for the same sources and changes with any local file it imports.
import { mkdir, mkdtemp, rm, writeFile } from 'node:fs/promises';
import { tmpdir } from 'node:os';
import { join } from 'node:path';
import { afterAll, beforeAll, describe, expect, it } from 'vitest';
import { getScenario } from '../../scenarios/index.ts';
import { isScenarioPath, loadScenarioModule, moduleSourceHash, scenarioModuleHash, ScenarioModuleError } from '../../server/scenario-module.ts';
import { REPO_DEFINE_SCENARIO, writeGameModule } from '../helpers/game-module.ts';

let dir = '';
beforeAll(async () => {
  dir = await mkdtemp(join(tmpdir(), 'taos-scenario-module-'));
});
afterAll(async () => {
  await rm(dir, { recursive: true, force: true });
});

async function sub(name: string): Promise<string> {
  const d = join(dir, name);
  await mkdir(d, { recursive: true });
  return d;
}

describe('scenario-module', () => {
  it('tells module paths from built-in names', () => {
    expect(isScenarioPath('./game.ts')).toBe(true);
    expect(isScenarioPath('game.js')).toBe(true);
    expect(isScenarioPath('/abs/game.mts')).toBe(true);
    expect(isScenarioPath('character-course')).toBe(false);
  });

  it('loads the export named scenario of a module and records its content hash', async () => {
    const path = await writeGameModule(await sub('a'));
    const def = await loadScenarioModule(path);
    expect(def.name).toBe('crate-drop');
    expect(def.params.crates.default).toBe(6);
    expect(await scenarioModuleHash(def)).toMatch(/^sha256:[0-9a-f]{64}$/);
    expect(await scenarioModuleHash(def)).toBe(await moduleSourceHash(path));
  });

  it('loads a default export too', async () => {
    const d = await sub('default');
    await writeFile(join(d, 'game.ts'), [`import { defineScenario } from '${REPO_DEFINE_SCENARIO}';`, "export default defineScenario({ name: 'plain', description: '', bounds: { min: { x: -1, y: -1, z: -1 }, max: { x: 1, y: 1, z: 1 } }, build: () => ({ spawnPoint: () => ({ x: 0, y: 0, z: 0 }) }) });"].join('\n'));
    expect((await loadScenarioModule(join(d, 'game.ts'))).name).toBe('plain');
  });

  it('gives built-in scenarios no module hash', async () => {
    expect(await scenarioModuleHash(getScenario('shape-rain'))).toBe('');
  });

  it('hashes the same sources alike and changes the hash when the module or a file it imports changes', async () => {
    const one = await writeGameModule(await sub('h1'));
    const same = await writeGameModule(await sub('h2'));
    const other = await writeGameModule(await sub('h3'), { crateHalfMetres: 0.5 });
    expect(await moduleSourceHash(one)).toBe(await moduleSourceHash(same));
    expect(await moduleSourceHash(other)).not.toBe(await moduleSourceHash(one));
    const d = await sub('h4');
    await writeFile(join(d, 'size.ts'), 'export const HALF = 0.4;\n');
    await writeFile(join(d, 'game.ts'), "import { HALF } from './size.ts';\nexport const size = HALF;\n");
    const before = await moduleSourceHash(join(d, 'game.ts'));
    await writeFile(join(d, 'size.ts'), 'export const HALF = 0.45;\n');
    expect(await moduleSourceHash(join(d, 'game.ts'))).not.toBe(before);
  });

  it('refuses a missing file, a module that throws, and a module without a defineScenario export', async () => {
    const d = await sub('bad');
    await expect(loadScenarioModule(join(d, 'nope.ts'))).rejects.toThrow(new ScenarioModuleError(`no such scenario module: ${join(d, 'nope.ts')}`));
    await writeFile(join(d, 'plain.ts'), "export const scenario = { name: 'x', build() {} };\nexport const other = 1;\n");
    await expect(loadScenarioModule(join(d, 'plain.ts'))).rejects.toThrow(/must export a defineScenario\(\.\.\.\) result as "scenario" .* it exports scenario, other/);
    await writeFile(join(d, 'throws.ts'), `import { defineScenario } from '${REPO_DEFINE_SCENARIO}';\nexport const scenario = defineScenario({ name: 'Bad Name' } as never);\n`);
    await expect(loadScenarioModule(join(d, 'throws.ts'))).rejects.toThrow(/cannot load scenario module .*throws\.ts: defineScenario\(Bad Name\): name must be/);
  });
});
