// Tests of the client build: the bundle and assets land in the output directory, a second build rewrites nothing,
// and a bundle that would pull in the physics engine is refused with the importer named.
import { mkdtemp, readFile, rm } from 'node:fs/promises';
import { tmpdir } from 'node:os';
import { join } from 'node:path';
import { afterAll, describe, expect, it } from 'vitest';
import { assertNoJolt, buildClient } from '../../scripts/build-client.ts';

describe('buildClient', () => {
  const dirs: string[] = [];
  afterAll(async () => {
    for (const d of dirs) await rm(d, { recursive: true, force: true });
  });

  it('bundles the page and the gallery with their assets, and a second build rewrites nothing', async () => {
    const outDir = await mkdtemp(join(tmpdir(), 'taos-client-'));
    dirs.push(outDir);
    const first = await buildClient({ outDir });
    expect(first.files).toEqual(expect.arrayContaining(['app.js', 'app.js.map', 'gallery.js', 'gallery.js.map', 'index.html', 'gallery.html', 'style.css']));
    expect(first.changed).toEqual(first.files);
    const html = await readFile(join(outDir, 'index.html'), 'utf8');
    expect(html).toContain('<script type="module" src="app.js">');
    const app = await readFile(join(outDir, 'app.js'), 'utf8');
    expect(app).not.toMatch(/jolt-physics|JoltInterface/);
    const second = await buildClient({ outDir });
    expect(second.changed).toEqual([]);
    expect(second.files).toEqual(first.files);
  });

  it('refuses a bundle that includes the physics engine, naming who imported it', () => {
    const meta = {
      inputs: {
        'client/app/oops.ts': { bytes: 10, imports: [{ path: 'node_modules/jolt-physics/dist/jolt-physics.wasm.js', kind: 'import-statement' as const, original: 'jolt-physics' }] },
        'node_modules/jolt-physics/dist/jolt-physics.wasm.js': { bytes: 1000, imports: [] },
      },
      outputs: {},
    };
    expect(() => assertNoJolt(meta)).toThrow(/must not include the physics engine: node_modules\/jolt-physics\/dist\/jolt-physics\.wasm\.js .* imported by client\/app\/oops\.ts/);
    expect(() => assertNoJolt({ inputs: { 'client/app/main.ts': { bytes: 1, imports: [] } }, outputs: {} })).not.toThrow();
  });
});
