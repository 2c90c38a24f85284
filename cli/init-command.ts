// `init NAME [--dependency SPEC] [--force]`: scaffolds a game project in ./NAME on the installed package (scaffold-files.ts): a scenario,
// a page, a test and a README. Refuses a folder that exists and is not empty, unless --force.
import { mkdir, readdir, stat, writeFile } from 'node:fs/promises';
import { basename, dirname, isAbsolute, join, relative, resolve } from 'node:path';
import { packageVersion } from '../server/package-root.ts';
import type { ParsedArgs } from './args.ts';
import { ExitCode, UsageError, type CliIo, type CommandSpec } from './command.ts';
import { scaffoldFiles } from './scaffold-files.ts';

const NAME_PATTERN = /^[a-z0-9][a-z0-9._-]{0,63}$/;

async function isEmptyOrMissing(dir: string): Promise<boolean> {
  try {
    return (await readdir(dir)).length === 0;
  } catch (err) {
    if ((err as NodeJS.ErrnoException).code === 'ENOENT') return true;
    if ((err as NodeJS.ErrnoException).code === 'ENOTDIR') throw new UsageError(`${dir} is a file, not a folder`);
    throw err;
  }
}

/**
 * What package.json says about taos-physics: this version's range by default; a given path (a tarball from
 * `npm pack`, or a folder) becomes `file:` relative to the project; any other text is used as it is.
 */
async function dependencySpec(given: string | undefined, target: string): Promise<string> {
  if (given === undefined) return `^${packageVersion()}`;
  if (given === '') throw new UsageError('--dependency must not be empty');
  const looksLikePath = given.endsWith('.tgz') || given.startsWith('.') || isAbsolute(given);
  if (!looksLikePath) return given;
  const full = resolve(given);
  try {
    await stat(full);
  } catch {
    throw new UsageError(`--dependency ${given}: no such file or folder`);
  }
  return `file:${relative(target, full).replace(/\\/g, '/')}`;
}

async function run(args: ParsedArgs, io: CliIo): Promise<number> {
  const target = resolve(args.positionals[0]);
  const name = basename(target);
  if (!NAME_PATTERN.test(name)) throw new UsageError(`"${name}" cannot be a project name: use 1-64 characters of a-z, 0-9, ".", "_" or "-", starting with a letter or digit`);
  if (!(await isEmptyOrMissing(target)) && !args.flag('force')) throw new UsageError(`${target} exists and is not empty (pass --force to write into it anyway)`);
  const files = scaffoldFiles({ name, dependency: await dependencySpec(args.string('dependency'), target) });
  for (const [path, text] of Object.entries(files)) {
    const full = join(target, path);
    await mkdir(dirname(full), { recursive: true });
    await writeFile(full, text);
  }
  const shown = relative(process.cwd(), target) || '.';
  io.stdout(`created ${shown}/ (${Object.keys(files).sort().join(', ')})\n\nnext:\n  cd ${shown}\n  npm install\n  npm start\n`);
  return ExitCode.Ok;
}

/** The init command. */
export const initCommand: CommandSpec = {
  name: 'init',
  summary: 'Create a game project (scenario, page, test, README) in a new folder',
  details: 'The project depends on this version of taos-physics; `npm install` then `npm start` serves it.',
  positionals: [{ name: 'NAME', description: 'folder to create; its name becomes the package and scenario name', required: true }],
  flags: [
    { name: 'dependency', kind: 'string', valueName: 'SPEC', description: 'taos-physics in package.json: a version range, or the path of a tarball from `npm pack` (default ^this version)' },
    { name: 'force', kind: 'boolean', description: 'write into a folder that is not empty (replacing files of the same names)' },
  ],
  run,
};
