// The command table: every CLI command, in help order. Adding a command = one file exporting a CommandSpec and
// one line here.
import { botsCommand } from './bots-command.ts';
import type { CommandSpec } from './command.ts';
import { goldensCommand } from './goldens-command.ts';
import { initCommand } from './init-command.ts';
import { inspectCommand } from './inspect-command.ts';
import { recordCommand } from './record-command.ts';
import { replayCommand } from './replay-command.ts';
import { runCommand } from './run-command.ts';
import { scenariosCommand } from './scenarios-command.ts';
import { serveCommand } from './serve-command.ts';
import { verifyCommand } from './verify-command.ts';

/** Every command, in the order `--help` lists them. */
export const COMMANDS: readonly CommandSpec[] = [runCommand, recordCommand, replayCommand, verifyCommand, inspectCommand, scenariosCommand, goldensCommand, serveCommand, botsCommand, initCommand];

/** The command called `name`, if any. */
export function findCommand(name: string): CommandSpec | undefined {
  return COMMANDS.find((c) => c.name === name);
}
