// Tests for `verify`: independent replays in child processes and in worker threads agree on every per-tick hash,
// and a log whose inputs no longer match its hashes fails verification.
import { mkdtemp, readFile, rm, writeFile } from 'node:fs/promises';
import { tmpdir } from 'node:os';
import { join } from 'node:path';
import { afterAll, beforeAll, describe, expect, it } from 'vitest';
import { firstHashDifference } from '../../cli/verify-command.ts';
import { cli, jsonOut, retouchTick } from '../helpers/cli.ts';

let dir = '';
let logPath = '';

beforeAll(async () => {
  dir = await mkdtemp(join(tmpdir(), 'taos-verify-'));
  logPath = join(dir, 'course.tlog');
  const r = await cli('record', '--scenario', 'character-course', '--bots', '2', '--ticks', '90', '--out', logPath, '--checkpoint-every', '30');
  if (r.code !== 0) throw new Error(r.stderr);
});
afterAll(async () => {
  await rm(dir, { recursive: true, force: true });
});

describe('verify-command', () => {
  it('passes when two child processes replay the log to the same 91 hashes', async () => {
    const r = await cli('verify', logPath, '--runs', '2', '--json');
    expect(r.code).toBe(0);
    expect(jsonOut(r)).toMatchObject({ runs: 2, mode: 'processes', ticks: 90, agree: true, matchesLog: true, differences: [], replay: null });
  });

  it('fails a log whose inputs were retouched, in worker threads', async () => {
    const path = join(dir, 'retouched.tlog');
    await writeFile(
      path,
      retouchTick(new Uint8Array(await readFile(logPath)), 20, (rec) => {
        rec.commands[0].input.buttons ^= 1; // toggle jump
        rec.commands[0].input.moveZ = rec.commands[0].input.moveZ === 0 ? 127 : 0;
      }),
    );
    const r = await cli('verify', path, '--workers');
    expect(r.code).toBe(1);
    expect(r.stdout).toBe('');
    expect(r.stderr).toMatch(/^verify: replay vs log: DIVERGED at tick 21 \(after applying tick record 20\)/);
  });

  it('finds the first tick at which two hash sequences differ', () => {
    expect(firstHashDifference(['a', 'b', 'c'], ['a', 'b', 'c'])).toBe(-1);
    expect(firstHashDifference(['a', 'b', 'c'], ['a', 'x', 'c'])).toBe(1);
    expect(firstHashDifference(['a', 'b', 'c'], ['a', 'b'])).toBe(2);
  });
});
