// Tests for the input-log file writer: complete logs, the flush/fsync policy, crash safety (a killed writer
// leaves a readable prefix), refusing to clobber files, and bad records that change nothing.
import { spawnSync } from 'node:child_process';
import { mkdtemp, readFile, rm, writeFile } from 'node:fs/promises';
import { tmpdir } from 'node:os';
import { join } from 'node:path';
import { afterAll, beforeAll, describe, expect, it } from 'vitest';
import { readLogBytes } from '../../../server/log/log-bytes.ts';
import { LogWriter } from '../../../server/log/log-writer.ts';
import { emptyTickInput } from '../../../shared/sim/types.ts';
import { fakeHash, sampleHeader, sampleTick } from '../../helpers/input-log.ts';

let dir = '';
beforeAll(async () => {
  dir = await mkdtemp(join(tmpdir(), 'taos-log-writer-'));
});
afterAll(async () => {
  await rm(dir, { recursive: true, force: true });
});

const read = async (path: string) => readLogBytes(await readFile(path), path);

describe('log-writer', () => {
  it('writes a complete log that reads back record for record', async () => {
    const path = join(dir, 'complete.taoslog');
    const w = await LogWriter.create(path, sampleHeader({ checkpointEveryTicks: 10 }));
    w.appendHash(0, fakeHash(0));
    for (let t = 0; t < 25; t++) {
      w.appendTick(sampleTick(t));
      w.appendHash(t + 1, fakeHash(t + 1));
      if ((t + 1) % 10 === 0) w.appendCheckpoint(t + 1, Uint8Array.of(t, 1, 2, 3));
    }
    await w.close(25, fakeHash(25));
    const { header, entries, outcome } = await read(path);
    expect(header.scenario).toBe('shape-rain');
    expect(outcome).toMatchObject({ status: 'complete', ticks: 25, validBytes: w.bytesWritten, fileBytes: w.bytesWritten });
    expect(entries.filter((e) => e.type === 'tick').map((e) => e.record)).toEqual(Array.from({ length: 25 }, (_, t) => sampleTick(t)));
    expect(entries.filter((e) => e.type === 'checkpoint').map((e) => [e.tick, [...e.bytes]])).toEqual([
      [10, [9, 1, 2, 3]],
      [20, [19, 1, 2, 3]],
    ]);
  });

  it('puts the header on disk at creation and hands records to the OS every flushEveryTicks ticks and at checkpoints', async () => {
    const path = join(dir, 'policy.taoslog');
    const w = await LogWriter.create(path, sampleHeader(), { flushEveryTicks: 10 });
    expect((await read(path)).outcome).toMatchObject({ status: 'unterminated', ticks: 0 });
    for (let t = 0; t < 9; t++) w.appendTick(sampleTick(t));
    await w.settled();
    expect((await read(path)).outcome.ticks).toBe(0);
    w.appendTick(sampleTick(9));
    await w.settled();
    expect((await read(path)).outcome.ticks).toBe(10);
    w.appendTick(sampleTick(10));
    w.appendCheckpoint(11, new Uint8Array(8));
    await w.settled();
    const mid = await read(path);
    expect(mid.outcome.ticks).toBe(11);
    expect(mid.entries.at(-1)).toMatchObject({ type: 'checkpoint', tick: 11 });
    await w.close(11, fakeHash(11));
    expect((await read(path)).outcome.status).toBe('complete');
  });

  it('leaves every flushed record readable when the writing process is killed', async () => {
    const path = join(dir, 'killed.taoslog');
    const script = `
      import { LogWriter } from ${JSON.stringify(new URL('../../../server/log/log-writer.ts', import.meta.url).pathname)};
      import { sampleHeader, sampleTick } from ${JSON.stringify(new URL('../../helpers/input-log.ts', import.meta.url).pathname)};
      const w = await LogWriter.create(${JSON.stringify(path)}, sampleHeader(), { flushEveryTicks: 60 });
      for (let t = 0; t < 150; t++) w.appendTick(sampleTick(t));
      await w.settled();
      process.kill(process.pid, 'SIGKILL');`;
    const scriptPath = join(dir, 'crash.ts');
    await writeFile(scriptPath, script);
    const res = spawnSync(process.execPath, [scriptPath], { encoding: 'utf8', timeout: 20_000 });
    expect(res.signal).toBe('SIGKILL');
    const { entries, outcome } = await read(path);
    expect(outcome.status).toBe('unterminated');
    expect(outcome.ticks).toBe(120);
    expect(entries.map((e) => (e.type === 'tick' ? e.record.tick : -1))).toEqual(Array.from({ length: 120 }, (_, t) => t));
  });

  it('rejects a bad record with a clear error and keeps the log valid and writable', async () => {
    const path = join(dir, 'bad-input.taoslog');
    const w = await LogWriter.create(path, sampleHeader());
    w.appendTick(sampleTick(0));
    expect(() => w.appendTick(sampleTick(5))).toThrow('input log: tick record for tick 5, expected tick 1');
    expect(() => w.appendTick({ ...emptyTickInput(1), commands: [{ playerId: 1, input: { moveX: Number.NaN, moveZ: 0, yaw: 0, pitch: 0, buttons: 0 } }] })).toThrow(/moveX must be finite/);
    expect(() => w.appendHash(0, fakeHash(0))).toThrow('input log: hash record for tick 0, but the log is at tick 1 (1 tick records written)');
    expect(() => w.appendHash(1, 'nothex')).toThrow(/16 lowercase hex digits/);
    w.appendTick(sampleTick(1));
    await expect(w.close(3, fakeHash(3))).rejects.toThrow(/end record for tick 3, but the log is at tick 2/);
    await w.close(2, fakeHash(2));
    expect(() => w.appendTick(sampleTick(2))).toThrow(/is closed/);
    const { entries, outcome } = await read(path);
    expect(outcome.status).toBe('complete');
    expect(entries.filter((e) => e.type === 'tick').map((e) => e.record)).toEqual([sampleTick(0), sampleTick(1)]);
  });

  it('refuses to overwrite an existing file unless asked, and rejects a bad header before creating anything', async () => {
    const path = join(dir, 'exists.taoslog');
    await writeFile(path, 'precious');
    await expect(LogWriter.create(path, sampleHeader())).rejects.toThrow(`${path} already exists (refusing to overwrite an input log; remove it or pass overwrite)`);
    expect(await readFile(path, 'utf8')).toBe('precious');
    const w = await LogWriter.create(path, sampleHeader(), { overwrite: true });
    await w.close(0, fakeHash(0));
    expect((await read(path)).outcome.status).toBe('complete');
    const fresh = join(dir, 'never.taoslog');
    await expect(LogWriter.create(fresh, sampleHeader({ params: { x: Number.NaN } }))).rejects.toThrow(/parameter x must be a finite number/);
    await expect(readFile(fresh)).rejects.toThrow(/ENOENT/);
    await expect(LogWriter.create(join(dir, 'x.taoslog'), sampleHeader(), { flushEveryTicks: 0 })).rejects.toThrow(/flushEveryTicks must be a positive integer/);
  });
});
