// Tests of the client build: the bundles and assets land in the output directory, a second build rewrites nothing,
// Jolt is split into a chunk under chunks/ that pages reach only by a dynamic import (the entry scripts and
// everything they load statically hold no Jolt byte), its .wasm is published under a content hash, and a build
// whose entry would load the engine statically is refused with the chain named.
import { createHash } from 'node:crypto';
import { existsSync } from 'node:fs';
import { mkdtemp, readdir, readFile, rm, writeFile } from 'node:fs/promises';
import { createRequire } from 'node:module';
import { tmpdir } from 'node:os';
import { dirname, join, normalize } from 'node:path';
import { afterAll, beforeAll, describe, expect, it } from 'vitest';
import { buildClient, checkEngineSplit, type BuildClientResult } from '../../scripts/build-client.ts';

const JOLT_MARKER = /JoltInterface|jolt-physics\.wasm\.wasm/;

/** The emitted scripts a page loads before any dynamic import: the entry and its static imports, transitively. */
async function staticClosure(outDir: string, entry: string): Promise<string[]> {
  const seen = new Set<string>([entry]);
  const queue = [entry];
  while (queue.length > 0) {
    const file = queue.shift()!;
    const text = await readFile(join(outDir, file), 'utf8');
    // Static forms only: `from"./x.js"` and bare `import"./x.js"`; `import("./x.js")` is dynamic and not followed.
    for (const m of text.matchAll(/(?:\bfrom\s*|\bimport\s*)"(\.{1,2}\/[^"]+)"/g)) {
      const target = normalize(join(dirname(file), m[1]));
      if (!seen.has(target)) {
        seen.add(target);
        queue.push(target);
      }
    }
  }
  return [...seen].sort();
}

describe('buildClient', () => {
  const dirs: string[] = [];
  let outDir: string;
  let first: BuildClientResult;

  beforeAll(async () => {
    outDir = await mkdtemp(join(tmpdir(), 'taos-client-'));
    dirs.push(outDir);
    first = await buildClient({ outDir });
  });

  afterAll(async () => {
    for (const d of dirs) await rm(d, { recursive: true, force: true });
  });

  it('bundles the page, the gallery and the replay viewer with their assets, and a second build rewrites nothing', async () => {
    expect(first.files).toEqual(expect.arrayContaining(['app.js', 'app.js.map', 'gallery.js', 'gallery.js.map', 'replay.js', 'index.html', 'gallery.html', 'replay.html', 'replay.css', 'style.css']));
    expect(first.changed).toEqual(first.files);
    const html = await readFile(join(outDir, 'index.html'), 'utf8');
    expect(html).toContain('<script type="module" src="app.js">');
    const second = await buildClient({ outDir });
    expect(second.changed).toEqual([]);
    expect(second.files).toEqual(first.files);
  });

  it('ships no Jolt byte with any page until it imports the physics chunk, which holds Jolt beside its content-hashed .wasm', async () => {
    for (const entry of ['app.js', 'gallery.js', 'replay.js']) {
      const closure = await staticClosure(outDir, entry);
      for (const file of closure) expect(await readFile(join(outDir, file), 'utf8'), `${entry} loads ${file} statically`).not.toMatch(JOLT_MARKER);
      expect(first.split.staticBytes[entry]).toBeGreaterThan(0);
    }
    expect(first.split.engineChunks).toContain(first.split.physicsChunk);
    for (const chunk of first.split.engineChunks) expect(chunk.startsWith('chunks/')).toBe(true);
    const engineText = (await Promise.all(first.split.engineChunks.map((c) => readFile(join(outDir, c), 'utf8')))).join('\n');
    expect(engineText).toMatch(/JoltInterface/);
    // The replay page reaches the engine, but only through import().
    const replay = await readFile(join(outDir, 'replay.js'), 'utf8');
    const replayClosure = await staticClosure(outDir, 'replay.js');
    const dynamic = [...(await Promise.all(replayClosure.map((f) => readFile(join(outDir, f), 'utf8')))).join('\n').matchAll(/\bimport\("(\.{1,2}\/[^"]+)"\)/g)];
    expect(dynamic.length, 'replay.js has no dynamic import').toBeGreaterThan(0);
    expect(replay).not.toMatch(JOLT_MARKER);

    const wasmFile = first.split.wasmFile!;
    expect(wasmFile).toMatch(/^chunks\/jolt-physics-[0-9a-f]{16}\.wasm$/);
    const published = await readFile(join(outDir, wasmFile));
    const original = await readFile(createRequire(import.meta.url).resolve('jolt-physics/jolt-physics.wasm.wasm'));
    expect(Buffer.compare(published, original)).toBe(0);
    expect(wasmFile).toContain(createHash('sha256').update(original).digest('hex').slice(0, 16));
    // The physics chunk names the published .wasm (the build defines it), so the page fetches exactly that file.
    const allChunks = first.files.filter((f) => f.startsWith('chunks/') && f.endsWith('.js'));
    const namers = [];
    for (const f of allChunks) if ((await readFile(join(outDir, f), 'utf8')).includes(wasmFile.slice('chunks/'.length))) namers.push(f);
    expect(namers.length).toBeGreaterThan(0);
  });

  it('removes chunks an earlier build left behind', async () => {
    await writeFile(join(outDir, 'chunks', 'physics-OLDHASH1.js'), 'stale');
    const again = await buildClient({ outDir });
    expect(existsSync(join(outDir, 'chunks', 'physics-OLDHASH1.js'))).toBe(false);
    expect((await readdir(join(outDir, 'chunks'))).map((f) => `chunks/${f}`).sort()).toEqual(again.files.filter((f) => f.startsWith('chunks/')));
  });

  it('refuses a build whose entry loads the physics engine statically, naming the chain', () => {
    const output = (inputs: string[], imports: Array<{ path: string; kind: 'import-statement' | 'dynamic-import' }>, entryPoint?: string) => ({
      bytes: 100,
      inputs: Object.fromEntries(inputs.map((i) => [i, { bytesInOutput: 10 }])),
      imports,
      exports: [],
      ...(entryPoint ? { entryPoint } : {}),
    });
    const meta = {
      inputs: {},
      outputs: {
        'dist/app.js': output(['client/app/main.ts'], [{ path: 'dist/chunks/shared-A.js', kind: 'import-statement' }], 'client/app/main.ts'),
        'dist/chunks/shared-A.js': output(['sdk/index.ts'], [{ path: 'dist/chunks/physics-B.js', kind: 'import-statement' }]),
        'dist/chunks/physics-B.js': output(['client/physics/index.ts', 'node_modules/jolt-physics/dist/jolt-physics.wasm.js'], [], 'client/physics/index.ts'),
      },
    };
    expect(() => checkEngineSplit(meta, 'dist', ['client/app/main.ts'])).toThrow(
      /entry app\.js \(client\/app\/main\.ts\) statically loads the physics engine: app\.js → chunks\/shared-A\.js → chunks\/physics-B\.js holds node_modules\/jolt-physics/,
    );
    meta.outputs['dist/chunks/shared-A.js'].imports = [{ path: 'dist/chunks/physics-B.js', kind: 'dynamic-import' }];
    expect(checkEngineSplit(meta, 'dist', ['client/app/main.ts'])).toEqual({ engineChunks: ['chunks/physics-B.js'], physicsChunk: 'chunks/physics-B.js', wasmFile: null, staticBytes: { 'app.js': 200 } });
  });
});
