// Tests for server/recorder.ts: a room's log holds the header, every applied record, periodic hashes and the end.
import { mkdtempSync, readFileSync, readdirSync, rmSync } from 'node:fs';
import { tmpdir } from 'node:os';
import { join } from 'node:path';
import { afterAll, describe, expect, it } from 'vitest';
import { readLogBytes } from '../../server/log/index.ts';
import { silentLogger } from '../../server/logger.ts';
import { createRoomRecorder, recordingFileName, type DurabilityMode } from '../../server/recorder.ts';
import type { TickInputRecord } from '../../shared/sim/types.ts';

const root = mkdtempSync(join(tmpdir(), 'taos-rec-'));
afterAll(() => rmSync(root, { recursive: true, force: true }));

const record = (tick: number): TickInputRecord => ({
  tick,
  leaves: tick === 5 ? [1] : [],
  joins: tick === 0 ? [{ playerId: 1, name: 'ann' }] : [],
  commands: tick > 0 && tick < 5 ? [{ playerId: 1, input: { moveX: tick, moveZ: 0, yaw: 0, pitch: 0, buttons: 0 } }] : [],
});

describe('recorder', () => {
  it('writes header, every tick record, periodic hashes and the end record', async () => {
    const dir = join(root, 'a');
    const rec = await createRoomRecorder({ dir, roomId: 'r1', scenario: 'character-course', params: { k: 2 }, seed: 7, startTick: 0, initialHash: '00000000000000aa', logger: silentLogger(), hashEveryTicks: 4, createdAt: new Date(Date.UTC(2024, 0, 2, 3, 4, 5)) });
    expect(rec.path).toBe(join(dir, 'r1-20240102T030405Z.taoslog'));
    for (let t = 0; t < 10; t++) {
      rec.append(record(t));
      rec.afterStep(t + 1, () => (t + 1).toString(16).padStart(16, '0'));
    }
    await rec.close(10, '00000000000000ff');
    const log = readLogBytes(new Uint8Array(readFileSync(rec.path)));
    expect(log.outcome.status).toBe('complete');
    expect(log.header).toMatchObject({ scenario: 'character-course', params: { k: 2 }, seed: 7, tickRateHz: 60, hashEveryTicks: 4 });
    const ticks = log.entries.flatMap((e) => (e.type === 'tick' ? [e.record] : []));
    expect(ticks).toEqual(Array.from({ length: 10 }, (_, t) => record(t)));
    const hashes = log.entries.flatMap((e) => (e.type === 'hash' ? [e.tick] : []));
    expect(hashes).toEqual([0, 4, 8]);
    expect(log.entries.find((e) => e.type === 'hash' && e.tick === 8)).toMatchObject({ hash: '0000000000000008' });
    expect(log.entries.at(-1)).toMatchObject({ type: 'end', tick: 10, hash: '00000000000000ff' });
  });

  it('leaves the log unterminated when the room failed mid-tick', async () => {
    const dir = join(root, 'b');
    const rec = await createRoomRecorder({ dir, roomId: 'r2', scenario: 's', params: {}, seed: 1, startTick: 0, initialHash: '0000000000000000', logger: silentLogger() });
    rec.append(record(0));
    rec.afterStep(1, () => '0000000000000001');
    rec.append(record(1)); // the step of tick 1 threw: the counter stays at 1
    await rec.close(1, null);
    const log = readLogBytes(new Uint8Array(readFileSync(rec.path)));
    expect(log.outcome.status).toBe('unterminated');
    expect(log.outcome.ticks).toBe(2);
  });

  it('refuses to start anywhere but tick 0 and never overwrites an earlier log', async () => {
    const dir = join(root, 'c');
    const base = { dir, roomId: 'r3', scenario: 's', params: {}, seed: 1, initialHash: '0000000000000000', logger: silentLogger(), createdAt: new Date(0) };
    await expect(createRoomRecorder({ ...base, startTick: 3 })).rejects.toThrow(/tick 0/);
    const a = await createRoomRecorder({ ...base, startTick: 0 });
    const b = await createRoomRecorder({ ...base, startTick: 0 });
    expect(a.path).not.toBe(b.path);
    await a.close(0, '0000000000000000');
    await b.close(0, '0000000000000000');
    expect(readdirSync(dir)).toHaveLength(2);
    expect(recordingFileName('x', new Date(0))).toBe('x-19700101T000000Z.taoslog');
  });

  it('in tick mode releases a tick only once its record is in the file, in tick order', async () => {
    const dir = join(root, 'd');
    const rec = await createRoomRecorder({ dir, roomId: 'r4', scenario: 's', params: {}, seed: 1, startTick: 0, initialHash: '0000000000000000', logger: silentLogger(), durability: { mode: 'tick' } });
    const seen: Array<{ tick: number; ticksOnDisk: number }> = [];
    const released = new Promise<void>((done) => {
      for (let t = 0; t < 30; t++) {
        rec.append(record(t));
        rec.afterStep(t + 1, () => (t + 1).toString(16).padStart(16, '0'));
        rec.release!(t, () => {
          seen.push({ tick: t, ticksOnDisk: readLogBytes(new Uint8Array(readFileSync(rec.path))).outcome.ticks });
          if (t === 29) done();
        });
      }
    });
    await released;
    expect(seen.map((s) => s.tick)).toEqual(Array.from({ length: 30 }, (_, t) => t));
    for (const s of seen) expect(s.ticksOnDisk).toBeGreaterThan(s.tick);
    expect(rec.syncs).toBeLessThan(30); // group commit: one sync covers the ticks appended while another ran
    await rec.close(30, '000000000000001e');
  });

  it('in interval mode writes records within the interval without holding ticks back', async () => {
    const dir = join(root, 'e');
    const rec = await createRoomRecorder({ dir, roomId: 'r5', scenario: 's', params: {}, seed: 1, startTick: 0, initialHash: '0000000000000000', logger: silentLogger(), durability: { mode: 'interval', intervalMs: 20 } });
    expect(rec.release).toBeUndefined();
    for (let t = 0; t < 5; t++) rec.append(record(t));
    const deadline = Date.now() + 5000;
    while (readLogBytes(new Uint8Array(readFileSync(rec.path))).outcome.ticks < 5 && Date.now() < deadline) await new Promise((r) => setTimeout(r, 10));
    expect(readLogBytes(new Uint8Array(readFileSync(rec.path))).outcome.ticks).toBe(5);
    await rec.close(5, '0000000000000005');
  });

  it('writes a checkpoint every C ticks and a last one before the end record', async () => {
    for (const mode of ['tick', 'interval', 'off'] as DurabilityMode[]) {
      const dir = join(root, `f-${mode}`);
      let taken = 0;
      const rec = await createRoomRecorder({ dir, roomId: 'r6', scenario: 's', params: {}, seed: 1, startTick: 0, initialHash: '0000000000000000', logger: silentLogger(), durability: { mode }, checkpointEveryTicks: 4, checkpoint: () => Uint8Array.of(++taken) });
      for (let t = 0; t < 10; t++) {
        rec.append(record(t));
        rec.afterStep(t + 1, () => (t + 1).toString(16).padStart(16, '0'));
      }
      await rec.close(10, '000000000000000a');
      const log = readLogBytes(new Uint8Array(readFileSync(rec.path)));
      expect(log.outcome.status).toBe('complete');
      expect(log.header.checkpointEveryTicks).toBe(4);
      const checkpoints = log.entries.flatMap((e) => (e.type === 'checkpoint' ? [[e.tick, e.bytes[0]]] : []));
      expect(checkpoints).toEqual([[4, 1], [8, 2], [10, 3]]);
    }
  });
  it.each(['tick', 'interval', 'off'] as const)('hands a log over mid-session and the recording that continues it ends one whole log (durability %s)', async (mode) => {
    const dir = join(root, `handoff-${mode}`);
    const base = { dir, roomId: 'moved', scenario: 's', params: {}, seed: 1, logger: silentLogger(), hashEveryTicks: 2, durability: { mode } };
    const first = await createRoomRecorder({ ...base, startTick: 0, initialHash: '0000000000000000' });
    const sent: number[] = [];
    for (let t = 0; t < 3; t++) {
      first.append(record(t));
      first.afterStep(t + 1, () => (t + 1).toString(16).padStart(16, '0'));
      if (first.release) first.release(t, () => sent.push(t));
      else sent.push(t);
    }
    const log = await first.handOff!();
    // Every send held for durability went out before the log changed hands.
    expect(sent).toEqual([0, 1, 2]);
    expect(log).toMatchObject({ path: first.path, ticks: 3 });
    first.append(record(3)); // too late for this thread: nothing is written
    const next = await createRoomRecorder({ ...base, startTick: 3, initialHash: '', continueLog: log! });
    for (let t = 3; t < 6; t++) {
      next.append(record(t));
      next.afterStep(t + 1, () => (t + 1).toString(16).padStart(16, '0'));
    }
    await next.close(6, '0000000000000006');
    const read = readLogBytes(new Uint8Array(readFileSync(first.path)));
    expect(read.outcome.status).toBe('complete');
    expect(read.entries.flatMap((e) => (e.type === 'tick' ? [e.record] : []))).toEqual(Array.from({ length: 6 }, (_, t) => record(t)));
    expect(read.entries.flatMap((e) => (e.type === 'hash' ? [e.tick] : []))).toEqual([0, 2, 4, 6]);
  });
});
