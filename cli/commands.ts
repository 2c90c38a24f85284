// The command table: every CLI command, in help order, each loaded only when it is run or listed (a command's module
// pulls in what it runs: `serve` the server, `bots` the client library; loading all of them slows every start).
// Adding a command = one file exporting a CommandSpec and one line here.
import type { CommandSpec } from './command.ts';

const LOADERS: ReadonlyArray<readonly [string, () => Promise<CommandSpec>]> = [
  ['run', async () => (await import('./run-command.ts')).runCommand],
  ['record', async () => (await import('./record-command.ts')).recordCommand],
  ['replay', async () => (await import('./replay-command.ts')).replayCommand],
  ['verify', async () => (await import('./verify-command.ts')).verifyCommand],
  ['inspect', async () => (await import('./inspect-command.ts')).inspectCommand],
  ['scenarios', async () => (await import('./scenarios-command.ts')).scenariosCommand],
  ['goldens', async () => (await import('./goldens-command.ts')).goldensCommand],
  ['serve', async () => (await import('./serve-command.ts')).serveCommand],
  ['bots', async () => (await import('./bots-command.ts')).botsCommand],
  ['init', async () => (await import('./init-command.ts')).initCommand],
];

/** Every command, in the order `--help` lists them. */
export async function loadCommands(): Promise<CommandSpec[]> {
  return Promise.all(LOADERS.map(([, load]) => load()));
}

/** The command called `name`, if any (only its module is loaded). */
export async function findCommand(name: string): Promise<CommandSpec | undefined> {
  const entry = LOADERS.find(([n]) => n === name);
  if (!entry) return undefined;
  const spec = await entry[1]();
  if (spec.name !== name) throw new Error(`command table: '${name}' loads the command '${spec.name}'`);
  return spec;
}
