// The CLI argument parser: `--flag value`, `--flag=value`, boolean flags, repeatable `--param k=v`, positionals,
// `--` to end flags. Every mistake (unknown flag, missing value, bad number, repeated flag) is a UsageError.
import { UsageError, type CommandSpec, type FlagSpec } from './command.ts';

type FlagValue = string | number | boolean | Record<string, number>;

/** Parsed command line of one command, with typed getters. */
export class ParsedArgs {
  readonly positionals: readonly string[];
  private readonly values: ReadonlyMap<string, FlagValue>;

  constructor(positionals: string[], values: Map<string, FlagValue>) {
    this.positionals = positionals;
    this.values = values;
  }

  /** Whether a flag was given. */
  has(name: string): boolean {
    return this.values.has(name);
  }

  /** A string flag, or undefined when absent. */
  string(name: string): string | undefined {
    const v = this.values.get(name);
    return typeof v === 'string' ? v : undefined;
  }

  /** A numeric (int or number) flag, or `fallback` when absent. */
  number(name: string, fallback: number): number;
  number(name: string): number | undefined;
  number(name: string, fallback?: number): number | undefined {
    const v = this.values.get(name);
    return typeof v === 'number' ? v : fallback;
  }

  /** A boolean flag (false when absent). */
  flag(name: string): boolean {
    return this.values.get(name) === true;
  }

  /** A repeatable key=value flag as an object (empty when absent). */
  pairs(name: string): Record<string, number> {
    const v = this.values.get(name);
    return typeof v === 'object' ? { ...v } : {};
  }
}

/** Whether argv asks for help (`-h`/`--help` before any `--`). */
export function wantsHelp(argv: readonly string[]): boolean {
  for (const a of argv) {
    if (a === '--') return false;
    if (a === '-h' || a === '--help') return true;
  }
  return false;
}

function parseNumber(spec: FlagSpec, raw: string): number {
  const label = `--${spec.name}`;
  let value: number;
  if (spec.kind === 'int') {
    if (!/^[-+]?\d+$/.test(raw)) throw new UsageError(`${label} must be an integer, got "${raw}"`);
    value = Number(raw);
    if (!Number.isSafeInteger(value)) throw new UsageError(`${label} is too large: ${raw}`);
  } else {
    value = raw.trim() === '' ? Number.NaN : Number(raw);
    if (!Number.isFinite(value)) throw new UsageError(`${label} must be a finite number, got "${raw}"`);
  }
  if (spec.min !== undefined && value < spec.min) throw new UsageError(`${label} must be ≥ ${spec.min}, got ${raw}`);
  if (spec.max !== undefined && value > spec.max) throw new UsageError(`${label} must be ≤ ${spec.max}, got ${raw}`);
  return value;
}

function parsePair(spec: FlagSpec, raw: string, into: Record<string, number>): void {
  const eq = raw.indexOf('=');
  const label = `--${spec.name}`;
  if (eq <= 0) throw new UsageError(`${label} takes key=value, got "${raw}"`);
  const key = raw.slice(0, eq);
  const text = raw.slice(eq + 1);
  const value = text.trim() === '' ? Number.NaN : Number(text);
  if (!Number.isFinite(value)) throw new UsageError(`${label} ${key} must be a finite number, got "${text}"`);
  if (Object.prototype.hasOwnProperty.call(into, key)) throw new UsageError(`${label} ${key} given twice`);
  into[key] = value;
}

function closest(name: string, options: readonly string[]): string | null {
  let best: string | null = null;
  let bestScore = 3;
  for (const o of options) {
    const d = editDistance(name, o);
    if (d < bestScore) {
      bestScore = d;
      best = o;
    }
  }
  return best;
}

/** Levenshtein distance (for "did you mean"). */
export function editDistance(a: string, b: string): number {
  let prev = Array.from({ length: b.length + 1 }, (_, j) => j);
  for (let i = 1; i <= a.length; i++) {
    const cur = [i];
    for (let j = 1; j <= b.length; j++) cur[j] = Math.min(prev[j] + 1, cur[j - 1] + 1, prev[j - 1] + (a[i - 1] === b[j - 1] ? 0 : 1));
    prev = cur;
  }
  return prev[b.length];
}

/** Suggests the closest of `options` to `name` as " (did you mean X?)", or "". */
export function didYouMean(name: string, options: readonly string[], prefix = ''): string {
  const c = closest(name, options);
  return c === null ? '' : ` (did you mean ${prefix}${c}?)`;
}

/** Parses a command's arguments (after the command name) against its spec. */
export function parseArgs(spec: CommandSpec, argv: readonly string[]): ParsedArgs {
  const byName = new Map(spec.flags.map((f) => [f.name, f]));
  const values = new Map<string, FlagValue>();
  const positionals: string[] = [];
  let flagsDone = false;
  for (let i = 0; i < argv.length; i++) {
    const arg = argv[i];
    if (flagsDone || !arg.startsWith('-') || arg === '-') {
      positionals.push(arg);
      continue;
    }
    if (arg === '--') {
      flagsDone = true;
      continue;
    }
    if (!arg.startsWith('--')) throw new UsageError(`unknown option ${arg} (flags are spelled --name)`);
    const eq = arg.indexOf('=');
    const name = eq >= 0 ? arg.slice(2, eq) : arg.slice(2);
    const f = byName.get(name);
    if (!f) throw new UsageError(`unknown flag --${name} for '${spec.name}'${didYouMean(name, [...byName.keys()], '--')}`);
    if (f.kind === 'boolean') {
      if (eq >= 0) throw new UsageError(`--${name} takes no value`);
      if (values.has(name)) throw new UsageError(`--${name} given twice`);
      values.set(name, true);
      continue;
    }
    let raw: string;
    if (eq >= 0) raw = arg.slice(eq + 1);
    else {
      if (i + 1 >= argv.length || (argv[i + 1].startsWith('--') && argv[i + 1].length > 2)) {
        throw new UsageError(`--${name} needs a value${f.valueName ? ` (${f.valueName})` : ''}`);
      }
      raw = argv[++i];
    }
    if (f.kind === 'pair') {
      const into = (values.get(name) as Record<string, number> | undefined) ?? {};
      parsePair(f, raw, into);
      values.set(name, into);
      continue;
    }
    if (values.has(name)) throw new UsageError(`--${name} given twice`);
    values.set(name, f.kind === 'string' ? raw : parseNumber(f, raw));
  }
  for (const f of spec.flags) {
    if (f.required && !values.has(f.name)) throw new UsageError(`missing --${f.name}${f.valueName ? ` ${f.valueName}` : ''}`);
  }
  const known = spec.positionals;
  for (let p = 0; p < known.length; p++) {
    if (known[p].required && positionals.length <= p) throw new UsageError(`missing ${known[p].name}`);
  }
  if (positionals.length > known.length) throw new UsageError(`unexpected argument "${positionals[known.length]}"`);
  return new ParsedArgs(positionals, values);
}
