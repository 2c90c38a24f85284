// Tests for the CLI argument parser: flag forms, typed values, repeatable key=value pairs, and clear errors.
import { describe, expect, it } from 'vitest';
import { editDistance, parseArgs, wantsHelp } from '../../cli/args.ts';
import { UsageError, type CommandSpec } from '../../cli/command.ts';

const spec: CommandSpec = {
  name: 'demo',
  summary: 'a demo command',
  positionals: [
    { name: 'FILE', description: 'input', required: true },
    { name: 'OUT', description: 'output', required: false },
  ],
  flags: [
    { name: 'scenario', kind: 'string', valueName: 'NAME', description: 'scenario', required: true },
    { name: 'ticks', kind: 'int', valueName: 'N', description: 'ticks', min: 0, max: 1000 },
    { name: 'scale', kind: 'number', valueName: 'X', description: 'scale' },
    { name: 'json', kind: 'boolean', description: 'json' },
    { name: 'param', kind: 'pair', valueName: 'k=v', description: 'params' },
  ],
  run: async () => 0,
};

const parse = (...argv: string[]) => parseArgs(spec, argv);
const usageError = (argv: string[]): string => {
  try {
    parseArgs(spec, argv);
  } catch (err) {
    expect(err).toBeInstanceOf(UsageError);
    return (err as Error).message;
  }
  throw new Error(`no error for ${argv.join(' ')}`);
};

describe('args', () => {
  it('reads --flag value, --flag=value, booleans, positionals and repeated key=value pairs', () => {
    const a = parse('in.taoslog', '--scenario', 'shape-rain', '--ticks=120', '--scale', '-0.5', '--json', '--param', 'count=40', '--param=spread=2.5', 'out');
    expect(a.positionals).toEqual(['in.taoslog', 'out']);
    expect(a.string('scenario')).toBe('shape-rain');
    expect(a.number('ticks')).toBe(120);
    expect(a.number('scale')).toBe(-0.5);
    expect(a.flag('json')).toBe(true);
    expect(a.pairs('param')).toEqual({ count: 40, spread: 2.5 });
    const b = parse('x', '--scenario', 's');
    expect(b.number('ticks', 600)).toBe(600);
    expect(b.flag('json')).toBe(false);
    expect(b.pairs('param')).toEqual({});
    expect(b.has('ticks')).toBe(false);
  });

  it('treats everything after -- as positionals', () => {
    expect(parse('--scenario', 's', '--', '--json').positionals).toEqual(['--json']);
  });

  it('names the mistake: unknown flag (with a suggestion), missing value, bad or out-of-range number, repeats', () => {
    expect(usageError(['f', '--scenario', 's', '--tick', '5'])).toBe("unknown flag --tick for 'demo' (did you mean --ticks?)");
    expect(usageError(['f', '--scenario', 's', '--frobnicate'])).toBe("unknown flag --frobnicate for 'demo'");
    expect(usageError(['f', '--scenario', 's', '-x'])).toBe('unknown option -x (flags are spelled --name)');
    expect(usageError(['f', '--scenario'])).toBe('--scenario needs a value (NAME)');
    expect(usageError(['f', '--scenario', '--json'])).toBe('--scenario needs a value (NAME)');
    expect(usageError(['f', '--scenario', 's', '--ticks', '12x'])).toBe('--ticks must be an integer, got "12x"');
    expect(usageError(['f', '--scenario', 's', '--ticks', '1.5'])).toBe('--ticks must be an integer, got "1.5"');
    expect(usageError(['f', '--scenario', 's', '--ticks', '5000'])).toBe('--ticks must be ≤ 1000, got 5000');
    expect(usageError(['f', '--scenario', 's', '--ticks', '-1'])).toBe('--ticks must be ≥ 0, got -1');
    expect(usageError(['f', '--scenario', 's', '--scale', 'NaN'])).toBe('--scale must be a finite number, got "NaN"');
    expect(usageError(['f', '--scenario', 's', '--scale', ''])).toBe('--scale must be a finite number, got ""');
    expect(usageError(['f', '--scenario', 's', '--ticks', '1', '--ticks', '2'])).toBe('--ticks given twice');
    expect(usageError(['f', '--scenario', 's', '--json', '--json'])).toBe('--json given twice');
    expect(usageError(['f', '--scenario', 's', '--json=yes'])).toBe('--json takes no value');
    expect(usageError(['f', '--scenario', 's', '--param', 'count'])).toBe('--param takes key=value, got "count"');
    expect(usageError(['f', '--scenario', 's', '--param', 'count=lots'])).toBe('--param count must be a finite number, got "lots"');
    expect(usageError(['f', '--scenario', 's', '--param', 'a=1', '--param', 'a=2'])).toBe('--param a given twice');
  });

  it('requires required flags and positionals and refuses extra positionals', () => {
    expect(usageError(['--scenario', 's'])).toBe('missing FILE');
    expect(usageError(['f'])).toBe('missing --scenario NAME');
    expect(usageError(['f', 'g', 'h', '--scenario', 's'])).toBe('unexpected argument "h"');
  });

  it('spots a help request before -- only', () => {
    expect(wantsHelp(['x', '--help'])).toBe(true);
    expect(wantsHelp(['-h'])).toBe(true);
    expect(wantsHelp(['--', '--help'])).toBe(false);
    expect(editDistance('replya', 'replay')).toBe(2);
  });
});
