// Where this package's files are: the folder holding its package.json, found from this module whether it runs from
// the repository's sources (server/) or from an installed package (dist/server/). Node only.
import { existsSync, readFileSync } from 'node:fs';
import { dirname, extname, join } from 'node:path';
import { fileURLToPath } from 'node:url';

const PACKAGE_NAME = 'taos-physics';

function findRoot(start: string): string {
  for (let dir = start; ; dir = dirname(dir)) {
    const manifest = join(dir, 'package.json');
    if (existsSync(manifest) && (JSON.parse(readFileSync(manifest, 'utf8')) as { name?: string }).name === PACKAGE_NAME) return dir;
    if (dirname(dir) === dir) throw new Error(`cannot find the ${PACKAGE_NAME} package.json above ${start}`);
  }
}

/** Absolute path of the package's root folder. */
export const PACKAGE_ROOT = findRoot(dirname(fileURLToPath(import.meta.url)));

/** The package's version (package.json). */
export function packageVersion(): string {
  return (JSON.parse(readFileSync(join(PACKAGE_ROOT, 'package.json'), 'utf8')) as { version: string }).version;
}

/**
 * The URL of a module beside `moduleUrl` (a worker's entry file), with the caller's own extension: `.ts` when running
 * from the sources, `.js` from the built package.
 */
export function siblingModuleUrl(moduleUrl: string, baseName: string): URL {
  return new URL(`./${baseName}${extname(fileURLToPath(moduleUrl))}`, moduleUrl);
}
