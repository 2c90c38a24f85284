// Tests for reading whole logs from memory: round trip, where corruption is reported, truncated tails, headers.
import { describe, expect, it } from 'vitest';
import { readLogBytes } from '../../../server/log/log-bytes.ts';
import { LogEncoder } from '../../../server/log/log-encoder.ts';
import { LogFormatError } from '../../../server/log/log-format.ts';
import { buildLog, fakeHash, sampleHeader, sampleTick } from '../../helpers/input-log.ts';

describe('log-bytes', () => {
  it('reads back every record of a log in order with its header', () => {
    const { header, entries, outcome } = readLogBytes(buildLog(100, { checkpointEvery: 25 }));
    expect(header).toEqual({ formatVersion: 2, ...sampleHeader({ checkpointEveryTicks: 25 }) });
    expect(outcome.status).toBe('complete');
    expect(outcome.ticks).toBe(100);
    const ticks = entries.filter((e) => e.type === 'tick').map((e) => e.record);
    expect(ticks).toEqual(Array.from({ length: 100 }, (_, t) => sampleTick(t)));
    const hashes = entries.filter((e) => e.type === 'hash');
    expect(hashes.map((h) => [h.tick, h.hash])).toEqual(Array.from({ length: 101 }, (_, t) => [t, fakeHash(t)]));
    expect(entries.filter((e) => e.type === 'checkpoint').map((c) => c.tick)).toEqual([25, 50, 75, 100]);
    expect(entries.at(-1)).toMatchObject({ type: 'end', tick: 100, hash: fakeHash(100) });
    expect(outcome.records).toBe(entries.length + 1);
  });

  it('reports a flipped byte at the record that holds it, with that record\'s byte offset, keeping all before it', () => {
    const log = buildLog(60);
    const clean = readLogBytes(log).entries;
    for (const victim of [clean[0], clean[17], clean[40], clean.at(-2)!, clean.at(-1)!]) {
      for (const within of [0, 1, 2, Math.floor(victim.sizeBytes / 2), victim.sizeBytes - 1]) {
        const bad = log.slice();
        bad[victim.offset + within] ^= 0x10;
        const { entries, outcome } = readLogBytes(bad);
        expect(outcome.status).toBe('corrupt');
        expect(outcome.corruption).toMatchObject({ recordIndex: victim.index, byteOffset: victim.offset });
        expect(entries).toEqual(clean.slice(0, victim.index - 1));
        expect(outcome.validBytes).toBe(victim.offset);
      }
    }
  });

  it('names the kind of damage: CRC, header check, unknown type, out-of-sequence tick', () => {
    const log = buildLog(10);
    const e = readLogBytes(log).entries[5];
    const reason = (mutate: (b: Uint8Array) => void): string => {
      const b = log.slice();
      mutate(b);
      return readLogBytes(b).outcome.corruption?.reason ?? 'none';
    };
    expect(reason((b) => (b[e.offset + e.sizeBytes - 6] ^= 1))).toMatch(/bad CRC in \w+ record/);
    expect(reason((b) => (b[e.offset + 1] ^= 1))).toMatch(/header check failed/);
    expect(reason((b) => (b[e.offset] = 0x7e))).toMatch(/unknown record type 0x7e/);
    // A well-formed record in the wrong place: swap in a tick record that skips a tick.
    const enc = new LogEncoder(sampleHeader());
    const parts = [enc.start(), enc.tick(sampleTick(0)), enc.tick(sampleTick(1))];
    enc.ticks = 3;
    parts.push(enc.tick(sampleTick(3)));
    const skipped = Uint8Array.from(parts.flatMap((p) => [...p]));
    expect(readLogBytes(skipped).outcome.corruption).toMatchObject({ recordIndex: 3, reason: 'tick record for tick 3 out of sequence (expected tick 2)' });
  });

  it('keeps every whole record before a truncated tail and reports it as truncated, not corrupt', () => {
    const log = buildLog(30);
    const clean = readLogBytes(log).entries;
    const cutRecord = clean[20];
    for (const cut of [1, 2, 3, cutRecord.sizeBytes - 1]) {
      const { entries, outcome } = readLogBytes(log.subarray(0, cutRecord.offset + cut));
      expect(outcome.status).toBe('truncated');
      expect(outcome.corruption).toBeUndefined();
      expect(entries).toEqual(clean.slice(0, 20));
      expect(outcome.validBytes).toBe(cutRecord.offset);
    }
    const atBoundary = readLogBytes(log.subarray(0, cutRecord.offset));
    expect(atBoundary.outcome.status).toBe('unterminated');
    expect(atBoundary.entries).toEqual(clean.slice(0, 20));
  });

  it('rejects data after the end record', () => {
    const log = buildLog(3);
    const tail = new LogEncoder(sampleHeader()).start().subarray(12);
    const { outcome } = readLogBytes(Uint8Array.from([...log, ...tail]));
    expect(outcome.corruption?.reason).toBe('data after the end record');
  });

  it('refuses files that are not input logs or have another format version, with a clear error', () => {
    const log = buildLog(2);
    expect(() => readLogBytes(new TextEncoder().encode('{"not":"a log"}'), 'x.json')).toThrow(new LogFormatError('x.json is not a taos-physics input log (bad magic bytes)'));
    const v3 = log.slice();
    v3[8] = 3;
    expect(() => readLogBytes(v3, 'a.taoslog')).toThrow('a.taoslog has input log format version 3; this build reads versions 1 and 2');
    expect(() => readLogBytes(new Uint8Array(0), 'e.taoslog')).toThrow('e.taoslog is empty');
    expect(() => readLogBytes(log.subarray(0, 6), 'p.taoslog')).toThrow(/truncated inside its 12-byte prelude/);
    expect(() => readLogBytes(log.subarray(0, 20), 'h.taoslog')).toThrow('h.taoslog is truncated inside its header record');
    const badHeader = log.slice();
    badHeader[20] ^= 0xff;
    expect(() => readLogBytes(badHeader, 'c.taoslog')).toThrow(/c.taoslog: no valid header: bad CRC in header record/);
  });
});
