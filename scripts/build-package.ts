// `npm run build`: the installable package. The browser page (build-client.ts) into dist/client, and the library and
// CLI as JavaScript with .d.ts types into dist/ (tsc -p tsconfig.build.json), import specifiers ending in .js, plus
// the scenarios' golden files. Old outputs are removed first, so nothing stale ships.
import { spawnSync } from 'node:child_process';
import { copyFile, readdir, readFile, rm, writeFile } from 'node:fs/promises';
import { dirname, join, resolve } from 'node:path';
import { fileURLToPath } from 'node:url';
import { buildClient } from './build-client.ts';

const REPO_ROOT = resolve(dirname(fileURLToPath(import.meta.url)), '..');
const DIST = join(REPO_ROOT, 'dist');
/** Source folders compiled into dist/ (tsconfig.build.json's include). */
export const LIBRARY_DIRS = ['api', 'shared', 'sdk', 'server', 'cli', 'scenarios'] as const;

async function filesUnder(dir: string, suffix: string): Promise<string[]> {
  const out: string[] = [];
  for (const entry of await readdir(dir, { withFileTypes: true, recursive: true })) {
    if (entry.isFile() && entry.name.endsWith(suffix)) out.push(join(entry.parentPath, entry.name));
  }
  return out;
}

/** Rewrites relative `.ts` specifiers in declaration files to `.js` (tsc rewrites them in JavaScript only). */
async function fixDeclarationSpecifiers(): Promise<number> {
  let changed = 0;
  for (const dir of LIBRARY_DIRS) {
    for (const file of await filesUnder(join(DIST, dir), '.d.ts')) {
      const text = await readFile(file, 'utf8');
      const fixed = text.replace(/((?:from|import)\s*\(?\s*['"])(\.{1,2}\/[^'"]+)\.ts(['"])/g, '$1$2.js$3');
      if (fixed !== text) {
        await writeFile(file, fixed);
        changed++;
      }
    }
  }
  return changed;
}

/** Builds everything; throws with the compiler's output when the code does not compile. */
export async function buildPackage(): Promise<{ durationMs: number }> {
  const started = performance.now();
  await buildClient();
  for (const dir of LIBRARY_DIRS) await rm(join(DIST, dir), { recursive: true, force: true });
  const tsc = spawnSync(process.execPath, [join(REPO_ROOT, 'node_modules', 'typescript', 'bin', 'tsc'), '-p', join(REPO_ROOT, 'tsconfig.build.json')], { encoding: 'utf8' });
  if (tsc.status !== 0) throw new Error(`tsc failed:\n${tsc.stdout}${tsc.stderr}`);
  await fixDeclarationSpecifiers();
  for (const name of await readdir(join(REPO_ROOT, 'scenarios'))) {
    if (name.endsWith('.golden.json')) await copyFile(join(REPO_ROOT, 'scenarios', name), join(DIST, 'scenarios', name));
  }
  return { durationMs: performance.now() - started };
}

if (process.argv[1] && resolve(process.argv[1]) === fileURLToPath(import.meta.url)) {
  try {
    const r = await buildPackage();
    console.log(`package built in ${(r.durationMs / 1000).toFixed(1)} s → dist/ (page, library, types, CLI)`);
  } catch (err) {
    console.error(`package build failed: ${(err as Error).message}`);
    process.exitCode = 1;
  }
}
