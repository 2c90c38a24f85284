// Tests for server/log/resume-point.ts and server/resume-rooms.ts through startServer({resumeDir}): interrupted logs
// reopen their rooms at their last intact tick with the recorded state, a damaged tail is cut (and kept aside), a
// log damaged in the middle is refused by record and left byte for byte as it was, and the whole session replays.
import { mkdir, mkdtemp, readdir, readFile, rm, writeFile } from 'node:fs/promises';
import { tmpdir } from 'node:os';
import { join } from 'node:path';
import { afterAll, beforeAll, describe, expect, it } from 'vitest';
import { nodePredictOptions } from '../../cli/predict-options.ts';
import { replayLog } from '../../cli/replay-session.ts';
import { connect } from '../../sdk/index.ts';
import { readLogBytes } from '../../server/log/log-bytes.ts';
import { findResumePoint } from '../../server/log/resume-point.ts';
import { silentLogger } from '../../server/logger.ts';
import { createMetrics } from '../../server/metrics.ts';
import { startServer } from '../../server/start-server.ts';
import { cli } from '../helpers/cli.ts';
import { buildLog } from '../helpers/input-log.ts';

let root = '';
/** A finished 200-tick recording (3 bots, a hash every tick, a checkpoint every 60 ticks). */
let complete: Uint8Array;
/** The same without its end record: what a crash leaves. */
let unterminated: Uint8Array;

const entriesOf = (bytes: Uint8Array) => readLogBytes(bytes).entries;
const tickEntry = (bytes: Uint8Array, tick: number) => entriesOf(bytes).find((e) => e.type === 'tick' && e.record.tick === tick)!;
const hashAt = (bytes: Uint8Array, tick: number) => entriesOf(bytes).flatMap((e) => (e.type === 'hash' && e.tick === tick ? [e.hash] : []))[0];

beforeAll(async () => {
  root = await mkdtemp(join(tmpdir(), 'taos-resume-'));
  const path = join(root, 'src.tlog');
  const r = await cli('record', '--scenario', 'character-course', '--bots', '3', '--ticks', '200', '--out', path, '--checkpoint-every', '60');
  if (r.code !== 0) throw new Error(r.stderr);
  complete = new Uint8Array(await readFile(path));
  const end = entriesOf(complete).at(-1)!;
  unterminated = complete.slice(0, end.offset);
});
afterAll(async () => {
  await rm(root, { recursive: true, force: true });
});

async function dirWith(name: string, files: Record<string, Uint8Array>): Promise<string> {
  const dir = join(root, name);
  await rm(dir, { recursive: true, force: true });
  await mkdir(dir);
  for (const [file, bytes] of Object.entries(files)) await writeFile(join(dir, file), bytes);
  return dir;
}

/** A torn last write: zeros from `from` to the end (the file keeps its length). */
function zeroTail(bytes: Uint8Array, from: number): Uint8Array {
  const out = bytes.slice();
  out.fill(0, from);
  return out;
}

function flipByte(bytes: Uint8Array, at: number): Uint8Array {
  const out = bytes.slice();
  out[at] ^= 0x40;
  return out;
}

describe('resume point', () => {
  it('finds the last checkpoint and the records after it in an unterminated log, and skips a complete one', async () => {
    const dir = await dirWith('points', { 'a.taoslog': unterminated, 'b.taoslog': complete });
    const p = await findResumePoint(join(dir, 'a.taoslog'));
    if ('kind' in p) throw new Error(`refused: ${JSON.stringify(p)}`);
    expect(p).toMatchObject({ ticks: 200, ending: 'unterminated', validBytes: unterminated.length, maxPlayerId: 3 });
    expect(p.checkpoint?.tick).toBe(180);
    expect(p.records.map((r) => r.tick)).toEqual(Array.from({ length: 20 }, (_, i) => 180 + i));
    expect(await findResumePoint(join(dir, 'b.taoslog'))).toEqual({ path: join(dir, 'b.taoslog'), kind: 'complete' });
  });

  it('cuts a partial or torn last write and refuses damage with intact records after it, naming the record', async () => {
    const last = tickEntry(unterminated, 199);
    const dir = await dirWith('damage', {
      'partial.taoslog': unterminated.slice(0, unterminated.length - 3),
      'tail.taoslog': zeroTail(unterminated, last.offset + 3),
      'middle.taoslog': flipByte(unterminated, tickEntry(unterminated, 50).offset + 3),
    });
    const partial = await findResumePoint(join(dir, 'partial.taoslog'));
    expect(partial).toMatchObject({ ending: 'truncated', validBytes: entriesOf(unterminated).at(-1)!.offset });
    const tail = await findResumePoint(join(dir, 'tail.taoslog'));
    expect(tail).toMatchObject({ ending: 'damaged-tail', ticks: 199, validBytes: last.offset });
    const middle = await findResumePoint(join(dir, 'middle.taoslog'));
    const record50 = tickEntry(unterminated, 50);
    expect(middle).toMatchObject({ kind: 'refused', recordIndex: record50.index, byteOffset: record50.offset });
    expect((middle as { reason: string }).reason).toMatch(new RegExp(`record #${record50.index} \\(byte offset ${record50.offset}\\) is damaged and intact records follow it`));
  });
});

describe('serve --resume (in-process)', () => {
  it('reopens the room at the last tick with the recorded state, goes on in the same log, and refuses a damaged log untouched', async () => {
    const middle = flipByte(unterminated, tickEntry(unterminated, 50).offset + 3);
    // foreign: shape-rain with a "spread" parameter this build does not declare, cut off like a crash.
    const foreign = buildLog(3, { end: false });
    const dir = await dirWith('serve', { 'default-20260101T000000Z.taoslog': unterminated, 'arena-20260101T000000Z.taoslog': middle, 'old-20250101T000000Z.taoslog': complete, 'rain-20260101T000000Z.taoslog': foreign });
    const server = await startServer({ port: 0, resumeDir: dir, recordDir: dir, recordHashEveryTicks: 1, logger: silentLogger(), metrics: createMetrics({ processMetrics: false }), clientDir: '/nonexistent-client-dir' });
    let closed = false;
    try {
      expect(server.resumed!.rooms.map((r) => [r.id, r.tick, r.hash])).toEqual([['default', 200, hashAt(unterminated, 200)]]);
      expect(server.resumed!.rooms[0].players.map((p) => p.playerId)).toEqual([1, 2, 3]);
      expect(server.resumed!.complete).toEqual([join(dir, 'old-20250101T000000Z.taoslog')]);
      const refused = server.resumed!.refused;
      expect(refused).toHaveLength(2);
      expect(refused[0]).toMatchObject({ path: join(dir, 'arena-20260101T000000Z.taoslog'), recordIndex: tickEntry(unterminated, 50).index });
      expect(refused[1]).toMatchObject({ path: join(dir, 'rain-20260101T000000Z.taoslog'), recordIndex: 0 });
      expect(refused[1].reason).toMatch(/its scenario cannot be built: .*unknown parameter "spread"/);
      expect(server.game.rooms.get('rain')).toBeUndefined();
      expect(server.game.rooms.get('arena')).toBeUndefined();
      const room = server.game.rooms.local('default')!;
      expect(room.sim.tick).toBeGreaterThanOrEqual(200);
      // No resume keys beside the log: the held players leave on the first tick (then the empty room pauses).
      const deadline = Date.now() + 5000;
      while ((room.sim.tick < 201 || room.clientCount > 0) && Date.now() < deadline) await new Promise((r) => setTimeout(r, 20));
      expect(room.clientCount).toBe(0);
      await server.close('test over');
      closed = true;
      expect(new Uint8Array(await readFile(join(dir, 'arena-20260101T000000Z.taoslog')))).toEqual(middle);
      expect(new Uint8Array(await readFile(join(dir, 'rain-20260101T000000Z.taoslog')))).toEqual(foreign);
      const report = await replayLog(join(dir, 'default-20260101T000000Z.taoslog'));
      expect(report).toMatchObject({ status: 'ok', log: 'complete' });
      expect(report.ticks).toBeGreaterThanOrEqual(201);
      expect(report.hashesChecked).toBe(report.ticks + 2); // initial, one per tick, the end record
      const leaves = entriesOf(new Uint8Array(await readFile(join(dir, 'default-20260101T000000Z.taoslog')))).flatMap((e) => (e.type === 'tick' && e.record.leaves.length > 0 ? [[e.record.tick, e.record.leaves]] : []));
      expect(leaves).toEqual([[200, [1, 2, 3]]]);
    } finally {
      if (!closed) await server.close('test over');
    }
  });

  it('goes on with predict mode: a predicting client confirms the resumed room\'s hashes while its players are held', async () => {
    // Resume keys for the three bots: they stay held, so the resumed room's records carry their held commands.
    const keys = new TextEncoder().encode([1, 2, 3].map((id) => `${id} ${String(id).repeat(43)}\n`).join(''));
    const dir = await dirWith('predict', { 'default-20260101T000000Z.taoslog': unterminated, 'default-20260101T000000Z.taoslog.resume': keys });
    const server = await startServer({ port: 0, resumeDir: dir, logger: silentLogger(), metrics: createMetrics({ processMetrics: false }), clientDir: '/nonexistent-client-dir' });
    const pred = connect(server.wsUrl, { name: 'pred', predict: nodePredictOptions(), reconnect: false });
    try {
      expect(server.game.listRooms()[0]).toMatchObject({ id: 'default', netMode: 'predict', clients: 3 });
      await pred.whenConnected();
      pred.setInput({ moveX: 0, moveZ: 127, yaw: 2000, pitch: 0, buttons: 0 });
      const deadline = performance.now() + 30_000;
      while ((pred.stats().prediction?.hashesVerified ?? 0) < 3 && performance.now() < deadline) await new Promise((r) => setTimeout(r, 25));
      expect(pred.stats().prediction).toMatchObject({ mode: 'predict', desyncs: 0 });
      expect(pred.stats().prediction!.hashesVerified).toBeGreaterThanOrEqual(3);
      expect(server.game.listRooms()[0].clients).toBe(4);
    } finally {
      pred.close();
      await server.close('test over');
    }
  });

  it('starts with nothing to resume when the directory does not exist yet, and records into it', async () => {
    const dir = join(root, 'fresh', 'rec');
    const server = await startServer({ port: 0, resumeDir: dir, recordDir: dir, logger: silentLogger(), metrics: createMetrics({ processMetrics: false }), clientDir: '/nonexistent-client-dir' });
    try {
      expect(server.resumed).toEqual({ rooms: [], refused: [], complete: [] });
      expect(server.game.rooms.get('default')).toBeDefined();
    } finally {
      await server.close('test over');
    }
    expect((await readdir(dir)).filter((f) => f.endsWith('.taoslog'))).toHaveLength(1);
  });

  it('resumes a log whose last records are torn from its last intact tick and keeps the cut bytes aside', async () => {
    const last = tickEntry(unterminated, 199);
    const damaged = zeroTail(unterminated, last.offset + 3);
    const dir = await dirWith('tail', { 'default-20260101T000000Z.taoslog': damaged });
    const server = await startServer({ port: 0, resumeDir: dir, logger: silentLogger(), metrics: createMetrics({ processMetrics: false }), clientDir: '/nonexistent-client-dir' });
    try {
      expect(server.resumed!.rooms.map((r) => [r.tick, r.hash])).toEqual([[199, hashAt(unterminated, 199)]]);
    } finally {
      await server.close('test over');
    }
    const files = await readdir(dir);
    expect(files).toContain(`default-20260101T000000Z.taoslog.tail-${last.offset}`);
    expect(new Uint8Array(await readFile(join(dir, `default-20260101T000000Z.taoslog.tail-${last.offset}`)))).toEqual(damaged);
    const report = await replayLog(join(dir, 'default-20260101T000000Z.taoslog'));
    expect(report).toMatchObject({ status: 'ok', log: 'complete' });
  });
});
