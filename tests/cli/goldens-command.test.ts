// Tests for `goldens`: --write stores a scenario's golden hash, a plain run checks it, and a wrong or missing
// golden fails with exit 1 without touching the file.
import { mkdtemp, readFile, rm, writeFile } from 'node:fs/promises';
import { tmpdir } from 'node:os';
import { join } from 'node:path';
import { afterAll, beforeAll, describe, expect, it } from 'vitest';
import { cli } from '../helpers/cli.ts';

let dir = '';
beforeAll(async () => {
  dir = await mkdtemp(join(tmpdir(), 'taos-goldens-'));
});
afterAll(async () => {
  await rm(dir, { recursive: true, force: true });
});

describe('goldens-command', () => {
  it('writes a golden only with --write, then checks it, and fails on a changed or missing hash', async () => {
    const args = ['goldens', '--scenario', 'character-course', '--dir', dir];
    const missing = await cli(...args);
    expect(missing.code).toBe(1);
    expect(missing.stdout).toMatch(/FAILED  character-course\s+no golden file .*character-course\.golden\.json \(create it with "goldens --write"\)/);

    const wrote = await cli(...args, '--write');
    expect(wrote.code).toBe(0);
    const path = join(dir, 'character-course.golden.json');
    const stored = JSON.parse(await readFile(path, 'utf8')) as { hash: string; ticks: number; bots: number };
    expect(stored).toMatchObject({ scenario: 'character-course', ticks: 300, bots: 3, joltVersion: '1.1.0' });
    expect(wrote.stdout).toContain(stored.hash);

    const ok = await cli(...args);
    expect(ok.code).toBe(0);
    expect(ok.stdout).toMatch(new RegExp(`^ok      character-course\\s+${stored.hash}`));

    const wrong = JSON.stringify({ ...stored, hash: '0123456789abcdef' });
    await writeFile(path, wrong);
    const bad = await cli(...args);
    expect(bad.code).toBe(1);
    expect(bad.stdout).toContain(`hash after 300 ticks is ${stored.hash}, golden says 0123456789abcdef`);
    expect(bad.stderr).toContain('1 of 1 scenario(s) differ from their golden');
    expect(await readFile(path, 'utf8')).toBe(wrong);
  });
});
