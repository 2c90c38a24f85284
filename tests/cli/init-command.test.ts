// Tests of `init NAME`: it writes the game project (package.json on this version, scenario, page, test, README with
// the two commands), refuses a bad name and a folder in use unless --force.
import { mkdir, mkdtemp, readFile, readdir, rm, writeFile } from 'node:fs/promises';
import { tmpdir } from 'node:os';
import { join } from 'node:path';
import { afterAll, beforeAll, describe, expect, it } from 'vitest';
import { packageVersion } from '../../server/package-root.ts';
import { cli } from '../helpers/cli.ts';

let dir = '';
beforeAll(async () => {
  dir = await mkdtemp(join(tmpdir(), 'taos-init-'));
});
afterAll(async () => {
  await rm(dir, { recursive: true, force: true });
});

describe('init-command', () => {
  it('creates a project depending on this version, with a scenario, a page, a test and a README', async () => {
    const target = join(dir, 'my-game');
    const r = await cli('init', target);
    expect(r.code, r.stderr).toBe(0);
    expect(r.stdout).toMatch(/npm install\n\s+npm start/);
    expect((await readdir(target, { recursive: true })).sort()).toEqual(['.gitignore', 'README.md', 'game.test.ts', 'game.ts', 'package.json', 'page', 'page/index.html', 'tsconfig.json']);
    const pkg = JSON.parse(await readFile(join(target, 'package.json'), 'utf8')) as Record<string, Record<string, string>>;
    expect(pkg.name).toBe('my-game');
    expect(pkg.dependencies).toEqual({ 'taos-physics': `^${packageVersion()}` });
    expect(pkg.scripts.start).toBe('taos-physics serve --scenario ./game.ts --page ./page');
    expect(await readFile(join(target, 'game.ts'), 'utf8')).toContain("name: 'my-game'");
    expect(await readFile(join(target, 'page', 'index.html'), 'utf8')).toContain("import { play } from '/kit.js'");
    expect(await readFile(join(target, 'README.md'), 'utf8')).toMatch(/npm install\nnpm start/);
  });

  it('points the dependency at a tarball path relative to the project, or at a given range', async () => {
    await writeFile(join(dir, 'taos-physics-9.9.9.tgz'), 'not really a tarball');
    expect((await cli('init', join(dir, 'from-tarball'), '--dependency', join(dir, 'taos-physics-9.9.9.tgz'))).code).toBe(0);
    const pkg = JSON.parse(await readFile(join(dir, 'from-tarball', 'package.json'), 'utf8')) as { dependencies: Record<string, string> };
    expect(pkg.dependencies['taos-physics']).toBe('file:../taos-physics-9.9.9.tgz');
    expect((await cli('init', join(dir, 'ranged'), '--dependency', '~0.1.2')).code).toBe(0);
    expect((JSON.parse(await readFile(join(dir, 'ranged', 'package.json'), 'utf8')) as { dependencies: Record<string, string> }).dependencies['taos-physics']).toBe('~0.1.2');
    const missing = await cli('init', join(dir, 'nowhere'), '--dependency', join(dir, 'missing.tgz'));
    expect(missing.code).toBe(2);
    expect(missing.stderr).toContain('no such file or folder');
  });

  it('refuses a folder that is not empty unless --force, and a name npm would refuse', async () => {
    const used = join(dir, 'used');
    await mkdir(used);
    await writeFile(join(used, 'notes.txt'), 'mine');
    const refused = await cli('init', used);
    expect(refused.code).toBe(2);
    expect(refused.stderr).toContain('exists and is not empty (pass --force');
    expect((await cli('init', used, '--force')).code).toBe(0);
    expect(await readFile(join(used, 'notes.txt'), 'utf8')).toBe('mine');
    const bad = await cli('init', join(dir, 'My Game'));
    expect(bad.code).toBe(2);
    expect(bad.stderr).toContain('"My Game" cannot be a project name');
  });
});
