// Tests for `inspect`: record counts and sizes by type, session length, and the integrity verdict of a log.
import { mkdtemp, rm, writeFile } from 'node:fs/promises';
import { tmpdir } from 'node:os';
import { join } from 'node:path';
import { afterAll, beforeAll, describe, expect, it } from 'vitest';
import { readLogBytes } from '../../server/log/log-bytes.ts';
import { cli, jsonOut } from '../helpers/cli.ts';
import { buildLog } from '../helpers/input-log.ts';

let dir = '';
beforeAll(async () => {
  dir = await mkdtemp(join(tmpdir(), 'taos-inspect-'));
});
afterAll(async () => {
  await rm(dir, { recursive: true, force: true });
});

describe('inspect-command', () => {
  it('counts records and bytes by type and reports the session length', async () => {
    const log = buildLog(120, { checkpointEvery: 60, players: 3 });
    const path = join(dir, 'a.taoslog');
    await writeFile(path, log);
    const r = await cli('inspect', path, '--json');
    expect(r.code).toBe(0);
    const info = jsonOut(r) as { records: Record<string, { records: number; bytes: number }>; [k: string]: unknown };
    expect(info).toMatchObject({ status: 'complete', ticks: 120, seconds: 2, maxPlayers: 3, fileBytes: log.length, corruption: null });
    expect(info.records.tick.records).toBe(120);
    expect(info.records.hash.records).toBe(121);
    expect(info.records.checkpoint.records).toBe(2);
    expect(info.records.end.records).toBe(1);
    const whole = readLogBytes(log).entries.reduce((n, e) => n + e.sizeBytes, 0);
    expect(Object.values(info.records).reduce((n, c) => n + c.bytes, 0)).toBe(whole);
    const text = await cli('inspect', path);
    expect(text.stdout).toContain('120 ticks (2.0 s at 60 Hz), up to 3 players');
    expect((info.checkpoints as Array<{ tick: number }>).map((c) => c.tick)).toEqual([60, 120]);
    expect(text.stdout).toContain('checkpoints: 2 at tick 60 (1.0 s), 120 (2.0 s)');
  });

  it('exits 1 on a corrupt log, naming the record, and 0 on a truncated one', async () => {
    const log = buildLog(40);
    const victim = readLogBytes(log).entries[30];
    const bad = log.slice();
    bad[victim.offset + victim.sizeBytes - 1] ^= 0xff;
    const path = join(dir, 'bad.taoslog');
    await writeFile(path, bad);
    const r = await cli('inspect', path);
    expect(r.code).toBe(1);
    expect(r.stdout).toContain(`status: corrupt at record #${victim.index} (byte offset ${victim.offset}): bad CRC`);
    const cut = join(dir, 'cut.taoslog');
    await writeFile(cut, log.subarray(0, victim.offset + 2));
    const t = await cli('inspect', cut);
    expect(t.code).toBe(0);
    expect(t.stdout).toContain('status: truncated (2 bytes of a partial record at the end)');
  });
});
