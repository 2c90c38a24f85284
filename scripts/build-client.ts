// Builds the browser page: esbuild bundles the client/app entries (with the sdk/ and shared/ code they import) into
// dist/client/, splits the physics chunk (client/physics/, Jolt included) into chunks/ beside Jolt's content-hashed
// .wasm, and copies the page assets. Entry scripts must not carry Jolt: pages load it with a dynamic import().
// Idempotent and cheap to call on every start: files are rewritten (atomically) only when their bytes changed.
import { createHash } from 'node:crypto';
import { build, type Metafile } from 'esbuild';
import { mkdir, readdir, readFile, rename, rm, writeFile } from 'node:fs/promises';
import { createRequire } from 'node:module';
import { dirname, join, relative, resolve } from 'node:path';
import { fileURLToPath } from 'node:url';

const REPO_ROOT = resolve(dirname(fileURLToPath(import.meta.url)), '..');
/** Where the built client goes by default (the server serves this directory). */
export const DEFAULT_CLIENT_OUT_DIR = join(REPO_ROOT, 'dist', 'client');
const CLIENT_DIR = join(REPO_ROOT, 'client');
/** Bundled entry points: source (relative to client/) → output name. */
const ENTRIES: Readonly<Record<string, string>> = { 'app/main.ts': 'app', 'app/gallery.ts': 'gallery', 'app/replay.ts': 'replay', 'kit/index.ts': 'kit' };
/** The physics chunk's module: pages reach it only by a dynamic import(). */
const PHYSICS_ENTRY = 'client/physics/index.ts';
/** Where split chunks and the .wasm go (content-hashed names: served as immutable). */
export const CHUNK_DIR = 'chunks';
/** Files at the top of client/ with these endings are copied as they are. */
const ASSET_PATTERN = /\.(html|css|svg|ico|png|txt)$/;

/** Options of buildClient. */
export interface BuildClientOptions {
  /** Output directory; default dist/client. */
  outDir?: string;
  /** Minify the bundle; default true. */
  minify?: boolean;
}

/** What a build produced. */
export interface BuildClientResult {
  outDir: string;
  /** Every output file, relative to outDir. */
  files: string[];
  /** The files whose bytes changed (written this time). */
  changed: string[];
  /** Total size of the outputs. */
  sizeBytes: number;
  durationMs: number;
  /** What the split put where: which scripts carry Jolt and how big each entry's static closure is. */
  split: EngineSplit;
}

/** Where the physics engine landed in a build. */
export interface EngineSplit {
  /** Output scripts (relative to outDir) holding Jolt or the physics wrapper: loaded only by dynamic import. */
  engineChunks: string[];
  /** The chunk built from client/physics/index.ts (what pages import()), relative to outDir; null if none. */
  physicsChunk: string | null;
  /** Jolt's .wasm, relative to outDir (null when no chunk needs it). */
  wasmFile: string | null;
  /** Per entry script: the bytes a page downloads before any dynamic import (the entry and its static imports). */
  staticBytes: Record<string, number>;
}

const require = createRequire(import.meta.url);

/** Jolt's .wasm bytes and the content-hashed name they are published under. */
async function joltWasm(): Promise<{ name: string; bytes: Uint8Array }> {
  const bytes = await readFile(require.resolve('jolt-physics/jolt-physics.wasm.wasm'));
  return { name: `jolt-physics-${createHash('sha256').update(bytes).digest('hex').slice(0, 16)}.wasm`, bytes };
}

/** Bundles and copies the client into outDir; throws with esbuild's messages if the code does not build. */
export async function buildClient(opts: BuildClientOptions = {}): Promise<BuildClientResult> {
  const started = performance.now();
  const outDir = resolve(opts.outDir ?? DEFAULT_CLIENT_OUT_DIR);
  const entryPoints = Object.entries(ENTRIES).map(([src, out]) => ({ in: join(CLIENT_DIR, src), out }));
  const wasm = await joltWasm();
  const result = await build({
    entryPoints,
    outdir: outDir,
    absWorkingDir: REPO_ROOT,
    bundle: true,
    splitting: true,
    chunkNames: `${CHUNK_DIR}/[name]-[hash]`,
    format: 'esm',
    platform: 'browser',
    // Jolt's glue imports node:module only on its Node path.
    external: ['node:module'],
    define: { __TAOS_JOLT_WASM_FILE__: JSON.stringify(wasm.name) },
    target: ['es2022', 'chrome113', 'firefox121', 'safari17'],
    minify: opts.minify ?? true,
    sourcemap: 'linked',
    write: false,
    metafile: true,
    logLevel: 'silent',
    legalComments: 'none',
  });
  const split = checkEngineSplit(result.metafile, relative(REPO_ROOT, outDir), entryPoints.map((e) => relative(REPO_ROOT, e.in)));
  const outputs = new Map<string, Uint8Array>();
  for (const file of result.outputFiles) outputs.set(relative(outDir, file.path), file.contents);
  if (split.engineChunks.length > 0) {
    split.wasmFile = `${CHUNK_DIR}/${wasm.name}`;
    outputs.set(split.wasmFile, wasm.bytes);
  }
  for (const name of (await readdir(CLIENT_DIR)).sort()) {
    if (ASSET_PATTERN.test(name)) outputs.set(name, await readFile(join(CLIENT_DIR, name)));
  }
  await mkdir(outDir, { recursive: true });
  const changed: string[] = [];
  let sizeBytes = 0;
  for (const [name, bytes] of outputs) {
    sizeBytes += bytes.byteLength;
    if (await writeIfChanged(join(outDir, name), bytes)) changed.push(name);
  }
  await pruneChunks(outDir, outputs);
  return { outDir, files: [...outputs.keys()].sort(), changed: changed.sort(), sizeBytes, durationMs: performance.now() - started, split };
}

/** Whether a bundled input is the physics engine (Jolt's glue or the wrapper that loads it). */
function isEngineInput(input: string): boolean {
  return /(^|\/)jolt-physics\//.test(input) || /(^|\/)shared\/physics\/(jolt-backend|physics-world)\.ts$/.test(input);
}

/**
 * Checks that no entry script reaches the physics engine through static imports (only a dynamic import() may load
 * it) and reports where it landed. Throws naming the entry, the chunk chain and the engine input otherwise.
 * `outDirFromRoot` is the output directory and `entrySources` the page entry points as the metafile names them
 * (relative to the repository root); dynamically imported modules are entry points to esbuild too, but not pages.
 */
export function checkEngineSplit(meta: Metafile, outDirFromRoot: string, entrySources: readonly string[]): EngineSplit {
  const prefix = outDirFromRoot === '' ? '' : `${outDirFromRoot.replace(/\/+$/, '')}/`;
  const local = (path: string): string => (path.startsWith(prefix) ? path.slice(prefix.length) : path);
  const scripts = Object.entries(meta.outputs).filter(([path]) => !path.endsWith('.map'));
  const engineChunks = scripts.filter(([, info]) => Object.keys(info.inputs).some(isEngineInput)).map(([path]) => local(path)).sort();
  const staticBytes: Record<string, number> = {};
  for (const [entryPath, entry] of scripts) {
    if (!entry.entryPoint || !entrySources.includes(entry.entryPoint)) continue;
    const cameFrom = new Map<string, string | null>([[entryPath, null]]);
    const queue = [entryPath];
    let bytes = 0;
    while (queue.length > 0) {
      const path = queue.shift()!;
      const info = meta.outputs[path];
      if (!info) continue;
      bytes += info.bytes;
      const engine = Object.entries(info.inputs).find(([input]) => isEngineInput(input));
      if (engine) {
        const chain: string[] = [];
        for (let at: string | null = path; at !== null; at = cameFrom.get(at)!) chain.unshift(local(at));
        throw new Error(
          `entry ${local(entryPath)} (${entry.entryPoint}) statically loads the physics engine: ${chain.join(' → ')} holds ${engine[0]} (${engine[1].bytesInOutput} bytes); ` +
            'load client/physics/ with a dynamic import() instead',
        );
      }
      for (const imp of info.imports) {
        if (imp.kind !== 'import-statement' || imp.external || cameFrom.has(imp.path)) continue;
        cameFrom.set(imp.path, path);
        queue.push(imp.path);
      }
    }
    staticBytes[local(entryPath)] = bytes;
  }
  const physics = scripts.find(([, info]) => info.entryPoint === PHYSICS_ENTRY);
  return { engineChunks, physicsChunk: physics ? local(physics[0]) : null, wasmFile: null, staticBytes };
}

/** Removes files under chunks/ that this build did not produce (older content-hashed chunks and .wasm). */
async function pruneChunks(outDir: string, outputs: ReadonlyMap<string, Uint8Array>): Promise<void> {
  let names: string[];
  try {
    names = await readdir(join(outDir, CHUNK_DIR));
  } catch {
    return;
  }
  for (const name of names) {
    if (!outputs.has(`${CHUNK_DIR}/${name}`)) await rm(join(outDir, CHUNK_DIR, name), { force: true });
  }
}

async function writeIfChanged(path: string, bytes: Uint8Array): Promise<boolean> {
  try {
    const existing = await readFile(path);
    if (Buffer.compare(existing, bytes) === 0) return false;
  } catch {
    // missing: write it
  }
  await mkdir(dirname(path), { recursive: true });
  // Write beside, then rename: a server reading the file never sees half of it.
  const tmp = `${path}.${process.pid}.${Math.floor(performance.now() * 1000)}.tmp`;
  await writeFile(tmp, bytes);
  await rename(tmp, path);
  return true;
}

async function main(argv: string[]): Promise<number> {
  const outIndex = argv.indexOf('--out');
  if (outIndex >= 0 && !argv[outIndex + 1]) {
    console.error('usage: node scripts/build-client.ts [--out DIR] [--no-minify]');
    return 2;
  }
  try {
    const r = await buildClient({ outDir: outIndex >= 0 ? argv[outIndex + 1] : undefined, minify: !argv.includes('--no-minify') });
    const what = r.changed.length ? `${r.changed.length} file(s) updated` : 'up to date';
    console.log(`client built in ${r.durationMs.toFixed(0)} ms → ${relative(process.cwd(), r.outDir) || '.'} (${r.files.length} files, ${(r.sizeBytes / 1024).toFixed(0)} KiB, ${what})`);
    return 0;
  } catch (err) {
    console.error(`client build failed: ${(err as Error).message}`);
    return 1;
  }
}

if (process.argv[1] && resolve(process.argv[1]) === fileURLToPath(import.meta.url)) {
  process.exitCode = await main(process.argv.slice(2));
}
