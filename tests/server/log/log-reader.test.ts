// Tests for the streaming file reader: same records as the in-memory reader, bounded memory on big logs,
// corruption thrown after the valid prefix, truncated tails kept.
import { mkdtemp, rm, writeFile } from 'node:fs/promises';
import { tmpdir } from 'node:os';
import { join } from 'node:path';
import { afterAll, beforeAll, describe, expect, it } from 'vitest';
import { readLogBytes } from '../../../server/log/log-bytes.ts';
import { LogEncoder } from '../../../server/log/log-encoder.ts';
import { LogCorruptError, LogFormatError, type LogEntry } from '../../../server/log/log-format.ts';
import { LogReader } from '../../../server/log/log-reader.ts';
import { buildLog, sampleHeader, sampleTick } from '../../helpers/input-log.ts';

let dir = '';
beforeAll(async () => {
  dir = await mkdtemp(join(tmpdir(), 'taos-log-reader-'));
});
afterAll(async () => {
  await rm(dir, { recursive: true, force: true });
});

async function readAll(path: string, chunkBytes?: number): Promise<{ reader: LogReader; entries: LogEntry[]; error: unknown }> {
  const reader = await LogReader.open(path, chunkBytes ? { chunkBytes } : {});
  const entries: LogEntry[] = [];
  let error: unknown = null;
  try {
    for await (const e of reader.entries()) entries.push(e);
  } catch (err) {
    error = err;
  }
  await reader.close();
  return { reader, entries, error };
}

describe('log-reader', () => {
  it('streams the same records as the in-memory reader at any chunk size', async () => {
    const log = buildLog(200, { checkpointEvery: 50 });
    const path = join(dir, 'same.taoslog');
    await writeFile(path, log);
    const expected = readLogBytes(log);
    for (const chunk of [64, 100, 4096, 1 << 20]) {
      const { reader, entries, error } = await readAll(path, chunk);
      expect(error).toBeNull();
      expect(reader.header).toEqual(expected.header);
      expect(entries).toEqual(expected.entries);
      expect(reader.outcome).toEqual(expected.outcome);
    }
  });

  it('reads a big log in a window no larger than one chunk or its largest record', async () => {
    const enc = new LogEncoder(sampleHeader({ checkpointEveryTicks: 20_000 }));
    const parts: Uint8Array[] = [enc.start()];
    const ticks = 60_000;
    const checkpoint = new Uint8Array(300_000).fill(7);
    for (let t = 0; t < ticks; t++) {
      parts.push(enc.tick(sampleTick(t, 4)));
      if ((t + 1) % 20_000 === 0) parts.push(enc.checkpoint(t + 1, checkpoint));
    }
    parts.push(enc.end(ticks, '0000000000000000'));
    const path = join(dir, 'big.taoslog');
    await writeFile(path, Buffer.concat(parts));
    const reader = await LogReader.open(path, { chunkBytes: 16 * 1024 });
    let tickCount = 0;
    let maxWindow = 0;
    let checkpoints = 0;
    for await (const e of reader.entries()) {
      if (e.type === 'tick') {
        expect(e.record.tick).toBe(tickCount);
        tickCount++;
      }
      if (e.type === 'checkpoint') {
        checkpoints++;
        expect(e.bytes).toEqual(checkpoint);
      }
      maxWindow = Math.max(maxWindow, reader.windowBytes);
    }
    await reader.close();
    expect(tickCount).toBe(ticks);
    expect(checkpoints).toBe(3);
    expect(reader.outcome?.status).toBe('complete');
    expect(maxWindow).toBeLessThanOrEqual(checkpoint.length + 16);
    expect(reader.windowBytes).toBeLessThanOrEqual(checkpoint.length + 16);
  });

  it('throws LogCorruptError naming the damaged record after yielding every record before it', async () => {
    const log = buildLog(80);
    const clean = readLogBytes(log).entries;
    const victim = clean[101];
    const bad = log.slice();
    bad[victim.offset + 3] ^= 0x01;
    const path = join(dir, 'flipped.taoslog');
    await writeFile(path, bad);
    const { reader, entries, error } = await readAll(path, 128);
    expect(error).toBeInstanceOf(LogCorruptError);
    expect(error).toMatchObject({ recordIndex: victim.index, byteOffset: victim.offset });
    expect(entries).toEqual(clean.slice(0, victim.index - 1));
    expect(entries).toHaveLength(101);
    expect(reader.outcome).toMatchObject({ status: 'corrupt', validBytes: victim.offset, fileBytes: log.length });
  });

  it('yields the prefix of a truncated log and reports the tail as truncated', async () => {
    const log = buildLog(80);
    const clean = readLogBytes(log).entries;
    const path = join(dir, 'cut.taoslog');
    await writeFile(path, log.subarray(0, clean[60].offset + 5));
    const { reader, entries, error } = await readAll(path, 64);
    expect(error).toBeNull();
    expect(entries).toEqual(clean.slice(0, 60));
    expect(reader.outcome).toMatchObject({ status: 'truncated', validBytes: clean[60].offset, fileBytes: clean[60].offset + 5 });
  });

  it('refuses a file that is not a log, and a log whose header is cut, when opening', async () => {
    const notLog = join(dir, 'notes.txt');
    await writeFile(notLog, 'hello world, definitely not a log');
    await expect(LogReader.open(notLog)).rejects.toThrow(new LogFormatError(`${notLog} is not a taos-physics input log (bad magic bytes)`));
    const cut = join(dir, 'header-cut.taoslog');
    await writeFile(cut, buildLog(1).subarray(0, 30));
    await expect(LogReader.open(cut)).rejects.toThrow(/truncated inside its header record/);
    await expect(LogReader.open(join(dir, 'missing.taoslog'))).rejects.toThrow(/ENOENT/);
  });
});
