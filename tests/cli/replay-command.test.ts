// Tests for `replay`: a recorded log replays with identical per-tick hashes; a retouched input is caught at the
// right tick, record and body; a damaged record is reported where it is; a truncated log replays its prefix.
import { mkdtemp, readFile, rm, writeFile } from 'node:fs/promises';
import { tmpdir } from 'node:os';
import { join } from 'node:path';
import { afterAll, beforeAll, describe, expect, it } from 'vitest';
import { readLogBytes } from '../../server/log/log-bytes.ts';
import { getScenario } from '../../scenarios/index.ts';
import { cli, jsonOut, retouchTick } from '../helpers/cli.ts';
import { buildLog } from '../helpers/input-log.ts';
import { crc32 } from '../../server/log/crc32.ts';

/** Flips the last hash byte of the hash record at `offset` and recomputes the record's CRC: well-framed, wrong hash. */
function rewriteHash(bytes: Uint8Array, offset: number, sizeBytes: number): Uint8Array {
  const end = offset + sizeBytes;
  bytes[end - 5] ^= 0xff;
  const crc = crc32(bytes, offset, end - 4);
  new DataView(bytes.buffer, bytes.byteOffset).setUint32(end - 4, crc, true);
  return bytes;
}

let dir = '';
let logPath = '';
let log: Uint8Array;

beforeAll(async () => {
  dir = await mkdtemp(join(tmpdir(), 'taos-replay-'));
  logPath = join(dir, 'course.taoslog');
  const r = await cli('record', '--scenario', 'character-course', '--bots', '3', '--ticks', '120', '--out', logPath, '--checkpoint-every', '40');
  if (r.code !== 0) throw new Error(r.stderr);
  log = new Uint8Array(await readFile(logPath)); // a plain copy: Buffer.slice would alias
});
afterAll(async () => {
  await rm(dir, { recursive: true, force: true });
});

const entriesOf = (bytes: Uint8Array) => readLogBytes(bytes).entries;

describe('replay-command', () => {
  it('reproduces every recorded per-tick hash', async () => {
    const r = await cli('replay', logPath, '--json', '--hashes');
    expect(r.code).toBe(0);
    const out = jsonOut(r);
    const recorded = entriesOf(log).flatMap((e) => (e.type === 'hash' ? [e.hash] : []));
    expect(recorded).toHaveLength(121);
    expect(out).toMatchObject({ status: 'ok', log: 'complete', ticks: 120, hashesChecked: 122, divergence: null, corruption: null });
    expect(out.hashes).toEqual(recorded);
    const text = await cli('replay', logPath);
    expect(text.stdout).toMatch(/^ok: 120 ticks of character-course \(seed 1\) replayed, 122 recorded hashes match, final hash [0-9a-f]{16}/);
  });

  it('stops at the first divergent tick after a retouched input and names the mismatching record and body', async () => {
    let playerId = -1;
    const tampered = retouchTick(log, 50, (rec) => {
      const c = rec.commands[0];
      playerId = c.playerId;
      c.input.moveX = c.input.moveX === 127 ? -127 : 127;
      c.input.moveZ = -127;
    });
    const path = join(dir, 'retouched.taoslog');
    await writeFile(path, tampered);
    const r = await cli('replay', path, '--json');
    expect(r.code).toBe(1);
    const out = jsonOut(r);
    const hash51 = entriesOf(tampered).find((e) => e.type === 'hash' && e.tick === 51)!;
    expect(out.status).toBe('diverged');
    expect(out.divergence).toMatchObject({ tick: 51, recordIndex: hash51.index, byteOffset: hash51.offset });
    const state = (out.divergence as { state: { checkpointTick: number; bodyId: number; body: string } }).state;
    expect(state.checkpointTick).toBe(80);
    expect(state.body).toBe(`player ${playerId}'s character`);
    const text = await cli('replay', path);
    expect(text.code).toBe(1);
    expect(text.stderr).toContain('DIVERGED at tick 51 (after applying tick record 50)');
    expect(text.stderr).toContain(`mismatching record: #${hash51.index} at byte offset ${hash51.offset}; 51 recorded hashes matched before it`);
    expect(text.stderr).toContain(`body ${state.bodyId}, player ${playerId}'s character`);
  });

  it('reports a flipped byte at the damaged record after replaying everything before it', async () => {
    const victim = entriesOf(log).find((e) => e.type === 'tick' && e.record.tick === 70)!;
    const bad = log.slice();
    bad[victim.offset + Math.floor(victim.sizeBytes / 2)] ^= 0x04;
    const path = join(dir, 'flipped.taoslog');
    await writeFile(path, bad);
    const r = await cli('replay', path, '--json');
    expect(r.code).toBe(1);
    const out = jsonOut(r);
    expect(out).toMatchObject({ status: 'corrupt', ticks: 70, hashesChecked: 71 });
    expect(out.corruption).toMatchObject({ recordIndex: victim.index, byteOffset: victim.offset, reason: expect.stringMatching(/bad CRC in tick record/) });
    const text = await cli('replay', path);
    expect(text.stderr).toMatch(new RegExp(`^CORRUPT LOG at record #${victim.index} \\(byte offset ${victim.offset}\\): bad CRC in tick record`));
  });

  it('reports a well-framed record the simulation cannot apply as corruption at that record', async () => {
    const tampered = retouchTick(log, 60, (rec) => {
      rec.joins = [{ playerId: rec.commands[0].playerId, name: 'again' }]; // a player who is already in the game
    });
    const victim = entriesOf(tampered).find((e) => e.type === 'tick' && e.record.tick === 60)!;
    const path = join(dir, 'unapplicable.taoslog');
    await writeFile(path, tampered);
    const out = jsonOut(await cli('replay', path, '--json'));
    expect(out).toMatchObject({ status: 'corrupt', log: 'corrupt', ticks: 60, hashesChecked: 61 });
    expect(out.corruption).toMatchObject({ recordIndex: victim.index, byteOffset: victim.offset, reason: expect.stringMatching(/^the simulation cannot apply tick record 60: .*cannot join, it is already in the game/) });
  });

  it('replays the whole records of a truncated log and says the tail was dropped', async () => {
    const cutAt = entriesOf(log).find((e) => e.type === 'tick' && e.record.tick === 100)!;
    const path = join(dir, 'truncated.taoslog');
    await writeFile(path, log.subarray(0, cutAt.offset + 3));
    const out = jsonOut(await cli('replay', path, '--json'));
    expect(out).toMatchObject({ status: 'ok', log: 'truncated', ticks: 100, hashesChecked: 101 });
    const text = await cli('replay', path);
    expect(text.code).toBe(0);
    expect(text.stdout).toContain('the log ends in a partial record (3 bytes');
  });

  it('stops at --to TICK with that tick\'s hash', async () => {
    const full = jsonOut(await cli('replay', logPath, '--json', '--hashes'));
    const out = jsonOut(await cli('replay', logPath, '--json', '--to', '33'));
    expect(out).toMatchObject({ status: 'ok', log: 'stopped', ticks: 33, hashesChecked: 34, finalHash: (full.hashes as string[])[33] });
  });

  it('starts --from TICK at the last checkpoint at or before it and matches the full replay\'s hashes from there', async () => {
    const full = jsonOut(await cli('replay', logPath, '--json', '--hashes'));
    const out = jsonOut(await cli('replay', logPath, '--json', '--from', '95'));
    // checkpoints every 40 ticks: 80 is the last at or before 95; 40 ticks replayed, its hash, 40 more and the end
    expect(out).toMatchObject({ status: 'ok', startTick: 80, ticks: 40, hashesChecked: 42, finalHash: (full.hashes as string[])[120] });
    const stopped = jsonOut(await cli('replay', logPath, '--json', '--from', '40', '--to', '50'));
    expect(stopped).toMatchObject({ status: 'ok', startTick: 40, ticks: 10, finalHash: (full.hashes as string[])[50] });
    const early = await cli('replay', logPath, '--from', '39');
    expect(early.code).toBe(0);
    expect(early.stderr).toContain('no checkpoint at or before tick 39: replayed from tick 0');
    expect((await cli('replay', logPath, '--from', '40', '--hashes')).code).toBe(2);
  });

  it('reports a checkpoint that does not restore to its recorded hash as a divergence at that tick', async () => {
    const entries = entriesOf(log);
    const hash80 = entries.find((e) => e.type === 'hash' && e.tick === 80)!;
    const bad = log.slice();
    // Rewrite the recorded hash at tick 80 (fixing its CRC) so the checkpoint restored there cannot match it.
    const path = join(dir, 'bad-hash.taoslog');
    await writeFile(path, rewriteHash(bad, hash80.offset, hash80.sizeBytes));
    const out = jsonOut(await cli('replay', path, '--json', '--from', '80'));
    expect(out).toMatchObject({ status: 'diverged', startTick: 80, ticks: 0 });
    expect((out.divergence as { tick: number; recordIndex: number }).recordIndex).toBe(hash80.index);
  });

  it('exits 1 when the log names a scenario or parameters this build does not have', async () => {
    const path = join(dir, 'foreign.taoslog');
    await writeFile(path, buildLog(3)); // shape-rain with a "spread" parameter it does not declare
    const r = await cli('replay', path);
    expect(r.code).toBe(1);
    expect(r.stderr).toBe(`taos-physics replay: ${path} cannot be replayed by this build: scenario shape-rain: unknown parameter "spread" (known: ${Object.keys(getScenario('shape-rain').params).join(', ')})\n`);
  });

  it('refuses a file that is not an input log', async () => {
    const path = join(dir, 'notes.txt');
    await writeFile(path, 'not a log at all');
    const r = await cli('replay', path);
    expect(r.code).toBe(1);
    expect(r.stderr).toBe(`taos-physics replay: ${path} is not a taos-physics input log (bad magic bytes)\n`);
  });
});
