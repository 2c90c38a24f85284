// Tests for `verify`: independent replays in child processes and in worker threads agree on every per-tick hash;
// a log whose inputs no longer match its hashes, or a damaged one, fails in both modes with the tick, record and
// byte offset, as `replay` reports them.
import { mkdtemp, readFile, rm, writeFile } from 'node:fs/promises';
import { tmpdir } from 'node:os';
import { join } from 'node:path';
import { afterAll, beforeAll, describe, expect, it } from 'vitest';
import { firstHashDifference } from '../../cli/verify-command.ts';
import { readLogBytes } from '../../server/log/log-bytes.ts';
import { cli, jsonOut, retouchTick } from '../helpers/cli.ts';

let dir = '';
let logPath = '';

beforeAll(async () => {
  dir = await mkdtemp(join(tmpdir(), 'taos-verify-'));
  logPath = join(dir, 'course.taoslog');
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
    const path = join(dir, 'retouched.taoslog');
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

  it('names the divergent tick, record, byte offset and body of a retouched log, in child processes', async () => {
    const tampered = retouchTick(new Uint8Array(await readFile(logPath)), 20, (rec) => {
      rec.commands[0].input.moveX = rec.commands[0].input.moveX === 127 ? -127 : 127;
      rec.commands[0].input.moveZ = -127;
    });
    const path = join(dir, 'diverged.taoslog');
    await writeFile(path, tampered);
    const hash21 = readLogBytes(tampered).entries.find((e) => e.type === 'hash' && e.tick === 21)!;
    const r = await cli('verify', path);
    expect(r.code).toBe(1);
    expect(r.stdout).toBe('');
    expect(r.stderr).toMatch(/^verify: replay vs log: DIVERGED at tick 21 \(after applying tick record 20\): the log says [0-9a-f]{16}, the replay computed [0-9a-f]{16}\n/);
    expect(r.stderr).toContain(`  mismatching record: #${hash21.index} at byte offset ${hash21.offset}; 21 recorded hashes matched before it\n`);
    expect(r.stderr).toMatch(/ {2}first difference \(body \d+, player \d+'s character\) against the recorded checkpoint at tick 30: /);
    const json = jsonOut(await cli('verify', path, '--json'));
    expect(json).toMatchObject({ agree: true, matchesLog: false, replay: { status: 'diverged', divergence: { tick: 21, recordIndex: hash21.index, byteOffset: hash21.offset }, corruption: null } });
  });

  it('names the damaged record and byte offset of a corrupt log, in child processes and in worker threads', async () => {
    const log = new Uint8Array(await readFile(logPath));
    const victim = readLogBytes(log).entries.find((e) => e.type === 'tick' && e.record.tick === 40)!;
    log[victim.offset + Math.floor(victim.sizeBytes / 2)] ^= 0x10;
    const path = join(dir, 'corrupt.taoslog');
    await writeFile(path, log);
    const expected = new RegExp(`^verify: replay vs log: CORRUPT LOG at record #${victim.index} \\(byte offset ${victim.offset}\\): bad CRC in tick record .*\\n {2}the 40 ticks before it replayed and all 41 recorded hashes matched\\n$`);
    for (const mode of [[], ['--workers']]) {
      const r = await cli('verify', path, ...mode);
      expect(r.code, mode.join(' ')).toBe(1);
      expect(r.stderr, mode.join(' ')).toMatch(expected);
      const json = jsonOut(await cli('verify', path, '--json', ...mode));
      expect(json).toMatchObject({ ticks: 40, agree: true, matchesLog: false, replay: { status: 'corrupt', divergence: null, corruption: { recordIndex: victim.index, byteOffset: victim.offset } } });
    }
  });

  it('finds the first tick at which two hash sequences differ', () => {
    expect(firstHashDifference(['a', 'b', 'c'], ['a', 'b', 'c'])).toBe(-1);
    expect(firstHashDifference(['a', 'b', 'c'], ['a', 'x', 'c'])).toBe(1);
    expect(firstHashDifference(['a', 'b', 'c'], ['a', 'b'])).toBe(2);
  });
});
