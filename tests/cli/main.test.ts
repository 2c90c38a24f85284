// Tests for the CLI entry: command dispatch, help, exit codes for bad arguments, run --json, and the bin wrapper.
import { spawnSync } from 'node:child_process';
import { fileURLToPath } from 'node:url';
import { describe, expect, it } from 'vitest';
import { loadCommands } from '../../cli/commands.ts';
import { cli, jsonOut } from '../helpers/cli.ts';

const BIN = fileURLToPath(new URL('../../bin/taos-physics.js', import.meta.url));

describe('main', () => {
  it('lists every command on --help and shows each command\'s flags on <command> --help', async () => {
    const commands = await loadCommands();
    const top = await cli('--help');
    expect(top.code).toBe(0);
    for (const c of commands) expect(top.stdout).toContain(c.name);
    for (const c of commands) {
      const r = await cli(c.name, '--help');
      expect(r.code).toBe(0);
      expect(r.stdout).toMatch(new RegExp(`^usage: taos-physics ${c.name}`));
      for (const f of c.flags) expect(r.stdout).toContain(`--${f.name}`);
    }
    expect((await cli('help', 'replay')).stdout).toContain('usage: taos-physics replay FILE');
  });

  it('exits 2 with a message and the usage on stderr for an unknown command or no command', async () => {
    const r = await cli('replya', 'x.taoslog');
    expect(r.code).toBe(2);
    expect(r.stdout).toBe('');
    expect(r.stderr).toMatch(/^taos-physics: unknown command 'replya' \(did you mean replay\?\)/);
    expect(r.stderr).toContain('usage: taos-physics <command>');
    expect((await cli()).code).toBe(2);
  });

  it('exits 2 naming the problem for bad flags, unknown scenarios, bad parameters, bad seeds and missing files', async () => {
    const cases: Array<[string[], RegExp]> = [
      [['run', '--scenario', 'character-course', '--ticks', 'ten'], /--ticks must be an integer, got "ten"/],
      [['run', '--scenario', 'character-course', '--tciks', '5'], /unknown flag --tciks for 'run' \(did you mean --ticks\?\)/],
      [['run', '--ticks', '5'], /missing --scenario NAME/],
      [['run', '--scenario'], /--scenario needs a value/],
      [['run', '--scenario', 'pendulum-chian'], /unknown scenario 'pendulum-chian' \(did you mean pendulum-chain\?\); known: .*shape-rain/],
      [['run', '--scenario', 'character-course', '--param', 'nope=1'], /unknown parameter "nope"/],
      [['run', '--scenario', 'character-course', '--param', 'crateRows=99'], /parameter crateRows must be in \[0, 8\], got 99/],
      [['run', '--scenario', 'character-course', '--seed', '-3'], /--seed must be an integer in \[0, 4294967295\] or a word/],
      [['record', '--scenario', 'character-course', '--bots', '2', '--ticks', '5'], /missing --out FILE/],
      [['replay', 'no-such-file.taoslog'], /no such file: no-such-file.taoslog/],
      [['replay'], /missing FILE/],
      [['verify', 'x.taoslog', '--runs', '1'], /--runs must be ≥ 2, got 1/],
    ];
    for (const [argv, message] of cases) {
      const r = await cli(...argv);
      expect(r.code, argv.join(' ')).toBe(2);
      expect(r.stderr, argv.join(' ')).toMatch(message);
      expect(r.stderr).toContain(`usage: taos-physics ${argv[0]}`);
      expect(r.stdout).toBe('');
    }
  });

  it('prints exactly {scenario, ticks, hash, msPerTick} for run --json, the same hash every run', async () => {
    const a = jsonOut(await cli('run', '--scenario', 'character-course', '--ticks', '40', '--bots', '2', '--json'));
    expect(Object.keys(a)).toEqual(['scenario', 'ticks', 'hash', 'msPerTick']);
    expect(a).toMatchObject({ scenario: 'character-course', ticks: 40 });
    expect(a.hash).toMatch(/^[0-9a-f]{16}$/);
    expect(a.msPerTick).toBeGreaterThan(0);
    const b = jsonOut(await cli('run', '--scenario', 'character-course', '--ticks', '40', '--bots', '2', '--json'));
    expect(b.hash).toBe(a.hash);
    const other = jsonOut(await cli('run', '--scenario', 'character-course', '--ticks', '40', '--bots', '2', '--seed', '7', '--json'));
    expect(other.hash).not.toBe(a.hash);
    const text = await cli('run', '--scenario', 'character-course', '--ticks', '40', '--bots', '2');
    expect(text.stdout).toMatch(new RegExp(`^character-course: 40 ticks, final hash ${a.hash} \\(\\d+\\.\\d+ ms/tick\\)\\n$`));
  });

  it('runs as a program through bin/taos-physics.js, passing exit codes through', () => {
    const ok = spawnSync(process.execPath, [BIN, 'run', '--scenario', 'character-course', '--ticks', '5', '--json'], { encoding: 'utf8', timeout: 30_000 });
    expect(ok.status).toBe(0);
    expect(JSON.parse(ok.stdout)).toMatchObject({ scenario: 'character-course', ticks: 5 });
    const bad = spawnSync(process.execPath, [BIN, 'frobnicate'], { encoding: 'utf8', timeout: 30_000 });
    expect(bad.status).toBe(2);
    expect(bad.stderr).toContain("unknown command 'frobnicate'");
  });
});
