// Help text of the CLI: the top-level command list and each command's usage, generated from the command specs
// so the help can never disagree with what the parser accepts.
import type { CommandSpec, FlagSpec } from './command.ts';

/** The program name in messages. */
export const PROGRAM = 'taos-physics';

function flagSynopsis(f: FlagSpec): string {
  const body = f.kind === 'boolean' ? `--${f.name}` : `--${f.name} ${f.valueName ?? 'VALUE'}`;
  const shown = f.kind === 'pair' ? `${body}…` : body;
  return f.required ? shown : `[${shown}]`;
}

/** One-line synopsis, e.g. "taos-physics replay FILE [--to TICK] [--json]". */
export function synopsis(spec: CommandSpec): string {
  const pos = spec.positionals.map((p) => (p.required ? p.name : `[${p.name}]`));
  return [PROGRAM, spec.name, ...pos, ...spec.flags.map(flagSynopsis)].join(' ');
}

function table(rows: [string, string][]): string {
  const width = Math.min(28, Math.max(...rows.map((r) => r[0].length)));
  return rows.map(([a, b]) => (a.length > width ? `  ${a}\n  ${' '.repeat(width)}  ${b}` : `  ${a.padEnd(width)}  ${b}`)).join('\n');
}

/** Full help of one command (`<command> --help`). */
export function commandHelp(spec: CommandSpec): string {
  const parts = [`usage: ${synopsis(spec)}`, '', spec.summary];
  if (spec.details) parts.push('', spec.details);
  if (spec.positionals.length > 0) parts.push('', 'arguments:', table(spec.positionals.map((p) => [p.name, p.description])));
  const flags: [string, string][] = spec.flags.map((f) => {
    const lhs = f.kind === 'boolean' ? `--${f.name}` : `--${f.name} ${f.valueName ?? 'VALUE'}`;
    const limits = f.min !== undefined || f.max !== undefined ? ` [${f.min ?? '-∞'}, ${f.max ?? '∞'}]` : '';
    return [lhs, `${f.description}${limits}${f.required ? ' (required)' : ''}`];
  });
  flags.push(['-h, --help', 'show this help']);
  parts.push('', 'flags:', table(flags));
  return parts.join('\n') + '\n';
}

/** The top-level help: every visible command with its summary. */
export function programHelp(commands: readonly CommandSpec[]): string {
  const visible = commands.filter((c) => !c.hidden);
  return [
    `usage: ${PROGRAM} <command> [arguments] [flags]`,
    '',
    'Deterministic Jolt physics server: headless runs, input logs, replays, verification.',
    '',
    'commands:',
    table(visible.map((c) => [c.name, c.summary])),
    '',
    `Run "${PROGRAM} <command> --help" for a command's flags. Exit codes: 0 ok, 1 check failed, 2 usage error.`,
    '',
  ].join('\n');
}
