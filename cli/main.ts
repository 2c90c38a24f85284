// CLI entry point: picks the command from the command table, parses its flags, runs it, and maps errors to exit
// codes (2 usage, 1 failure). Returns the exit code; never calls process.exit, so tests can call it in-process.
import { parseArgs, didYouMean, wantsHelp } from './args.ts';
import { ExitCode, UsageError, type CliIo } from './command.ts';
import { findCommand, loadCommands } from './commands.ts';
import { commandHelp, PROGRAM, programHelp } from './usage.ts';

/** Output to the process's own streams. */
export function processIo(): CliIo {
  return {
    stdout: (text) => void process.stdout.write(text),
    stderr: (text) => void process.stderr.write(text),
    stderrIsTTY: process.stderr.isTTY === true,
  };
}

/** Runs the CLI with `argv` (arguments after the program name); resolves to the exit code. */
export async function main(argv: readonly string[], io: CliIo = processIo()): Promise<number> {
  const [name, ...rest] = argv;
  if (name === undefined) {
    io.stderr(programHelp(await loadCommands()));
    return ExitCode.Usage;
  }
  if (name === '--help' || name === '-h' || name === 'help') {
    const topic = name === 'help' ? rest[0] : undefined;
    if (topic === undefined) {
      io.stdout(programHelp(await loadCommands()));
      return ExitCode.Ok;
    }
    const spec = await findCommand(topic);
    if (!spec) return unknownCommand(topic, io);
    io.stdout(commandHelp(spec));
    return ExitCode.Ok;
  }
  if (name === '--version') {
    io.stdout(`${PROGRAM} ${await packageVersion()}\n`);
    return ExitCode.Ok;
  }
  const spec = await findCommand(name);
  if (!spec) return unknownCommand(name, io);
  if (wantsHelp(rest)) {
    io.stdout(commandHelp(spec));
    return ExitCode.Ok;
  }
  try {
    const args = parseArgs(spec, rest);
    return await spec.run(args, io);
  } catch (err) {
    if (err instanceof UsageError) {
      io.stderr(`${PROGRAM} ${spec.name}: ${err.message}\n\n${commandHelp(spec)}`);
      return ExitCode.Usage;
    }
    const e = err as Error;
    io.stderr(`${PROGRAM} ${spec.name}: ${e?.message ?? String(err)}\n`);
    if (process.env.TAOS_DEBUG && e?.stack) io.stderr(`${e.stack}\n`);
    return ExitCode.Failed;
  }
}

async function unknownCommand(name: string, io: CliIo): Promise<number> {
  const commands = await loadCommands();
  const names = commands.filter((c) => !c.hidden).map((c) => c.name);
  io.stderr(`${PROGRAM}: unknown command '${name}'${didYouMean(name, names)}\n\n${programHelp(commands)}`);
  return ExitCode.Usage;
}

async function packageVersion(): Promise<string> {
  const { packageVersion: version } = await import('../server/package-root.ts');
  return version();
}
