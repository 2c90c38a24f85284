// The CLI's command contract: what a command declares (name, summary, positionals, flags) and receives (parsed
// arguments, an output sink), plus the errors that map to exit codes. Commands are listed in commands.ts.
import type { ParsedArgs } from './args.ts';

/** Exit codes of every command. */
export const ExitCode = {
  Ok: 0,
  /** A check failed: hash divergence, corrupt log, runs that disagree, a golden mismatch. */
  Failed: 1,
  /** The command line or its inputs are wrong: unknown command/flag/scenario, bad value. */
  Usage: 2,
} as const;

/** How a flag's value is read. `pair`: repeatable `key=number`; other kinds may be given once. */
export type FlagKind = 'string' | 'int' | 'number' | 'boolean' | 'pair';

/** One `--flag` a command accepts. */
export interface FlagSpec {
  name: string;
  kind: FlagKind;
  /** Placeholder in usage text, e.g. "N" for --ticks N. */
  valueName?: string;
  description: string;
  /** The command cannot run without it. */
  required?: boolean;
  /** Inclusive limits for int/number flags. */
  min?: number;
  max?: number;
}

/** One positional argument. */
export interface PositionalSpec {
  name: string;
  description: string;
  required: boolean;
}

/** Where a command writes: stdout for results, stderr for progress and diagnostics. */
export interface CliIo {
  stdout(text: string): void;
  stderr(text: string): void;
  /** Whether stderr is an interactive terminal (progress bars only then). */
  readonly stderrIsTTY: boolean;
}

/** A CLI command. Adding one = one file exporting a CommandSpec + one line in commands.ts. */
export interface CommandSpec {
  name: string;
  /** One line for the command list. */
  summary: string;
  /** Paragraph shown by `<command> --help` under the usage line. */
  details?: string;
  positionals: readonly PositionalSpec[];
  flags: readonly FlagSpec[];
  /** Hidden commands run but are not listed (internal helpers). */
  hidden?: boolean;
  /** Runs the command; returns the exit code. Throw UsageError for bad input (exit 2). */
  run(args: ParsedArgs, io: CliIo): Promise<number>;
}

/** Bad command line or inputs: printed with the command's usage, exit code 2. */
export class UsageError extends Error {
  override name = 'UsageError';
}
