// Builds the browser page: esbuild bundles the client/app entries (with the sdk/ and shared/ code they import) into
// dist/client/ and copies the page assets.
// Idempotent and cheap to call on every start: files are rewritten (atomically) only when their bytes changed.
import { build, type Metafile } from 'esbuild';
import { mkdir, readdir, readFile, rename, writeFile } from 'node:fs/promises';
import { dirname, join, relative, resolve } from 'node:path';
import { fileURLToPath } from 'node:url';

const REPO_ROOT = resolve(dirname(fileURLToPath(import.meta.url)), '..');
/** Where the built client goes by default (the server serves this directory). */
export const DEFAULT_CLIENT_OUT_DIR = join(REPO_ROOT, 'dist', 'client');
const CLIENT_DIR = join(REPO_ROOT, 'client');
/** Bundled entry points: source (relative to client/) → output name. */
const ENTRIES: Readonly<Record<string, string>> = { 'app/main.ts': 'app', 'app/gallery.ts': 'gallery', 'kit/index.ts': 'kit' };
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
}

/** Bundles and copies the client into outDir; throws with esbuild's messages if the code does not build. */
export async function buildClient(opts: BuildClientOptions = {}): Promise<BuildClientResult> {
  const started = performance.now();
  const outDir = resolve(opts.outDir ?? DEFAULT_CLIENT_OUT_DIR);
  const entryPoints = Object.entries(ENTRIES).map(([src, out]) => ({ in: join(CLIENT_DIR, src), out }));
  const result = await build({
    entryPoints,
    outdir: outDir,
    bundle: true,
    format: 'esm',
    platform: 'browser',
    target: ['es2022', 'chrome113', 'firefox121', 'safari17'],
    minify: opts.minify ?? true,
    sourcemap: 'linked',
    write: false,
    metafile: true,
    logLevel: 'silent',
    legalComments: 'none',
  });
  assertNoJolt(result.metafile);
  const outputs = new Map<string, Uint8Array>();
  for (const file of result.outputFiles) outputs.set(relative(outDir, file.path), file.contents);
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
  return { outDir, files: [...outputs.keys()].sort(), changed: changed.sort(), sizeBytes, durationMs: performance.now() - started };
}

/** Throws, naming the importer, if a bundle pulled in the physics engine: the browser only draws what the server says. */
export function assertNoJolt(meta: Metafile): void {
  for (const [input, info] of Object.entries(meta.inputs)) {
    if (/(^|\/)jolt-physics\//.test(input) || /(^|\/)shared\/physics\/(jolt-backend|physics-world)\.ts$/.test(input)) {
      const importers = Object.entries(meta.inputs)
        .filter(([, other]) => other.imports.some((imp) => imp.path === input))
        .map(([name]) => name);
      throw new Error(`client bundle must not include the physics engine: ${input} (${info.bytes} bytes) is imported by ${importers.join(', ') || 'an entry point'}`);
    }
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
