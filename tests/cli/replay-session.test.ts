// Tests of replayLog and the log reader on hostile files (a log is stranger input too): flipped bytes, cuts,
// well-framed records with random payloads, out-of-order and semantically impossible records, damaged headers.
// Every one is reported (ok, diverged or corrupt with its record and byte offset) or refused as not a log; none
// escapes as another exception.
import { mkdtemp, readFile, rm, writeFile } from 'node:fs/promises';
import { tmpdir } from 'node:os';
import { join } from 'node:path';
import { afterAll, beforeAll, describe, expect, it } from 'vitest';
import { replayLog } from '../../cli/replay-session.ts';
import { ByteWriter } from '../../shared/byte-io.ts';
import { encodeFrame } from '../../server/log/frame.ts';
import { readLogBytes } from '../../server/log/log-bytes.ts';
import { LogCorruptError, LogFormatError, RecordType, type LogEntry, type RecordTypeCode } from '../../server/log/log-format.ts';
import { LogReader } from '../../server/log/log-reader.ts';
import { Prng } from '../../shared/sim/prng.ts';
import { cli, retouchTick } from '../helpers/cli.ts';

let dir = '';
let log: Uint8Array;
let entries: LogEntry[];

beforeAll(async () => {
  dir = await mkdtemp(join(tmpdir(), 'taos-hostile-log-'));
  const path = join(dir, 'course.taoslog');
  const r = await cli('record', '--scenario', 'character-course', '--param', 'crateRows=0', '--bots', '2', '--ticks', '40', '--out', path, '--checkpoint-every', '10');
  if (r.code !== 0) throw new Error(r.stderr);
  log = new Uint8Array(await readFile(path));
  entries = readLogBytes(log).entries;
});
afterAll(async () => {
  await rm(dir, { recursive: true, force: true });
});

/** A tick payload written byte by byte, without the writer's checks: any ids, any counts. */
function rawTickPayload(tick: number, leaves: number[], joins: number[], commands: number[]): Uint8Array {
  const w = new ByteWriter();
  w.uvarint(tick);
  w.uvarint(leaves.length);
  for (const id of leaves) w.uvarint(id);
  w.uvarint(joins.length);
  for (const id of joins) {
    w.uvarint(id);
    w.varintPrefixedString(`p${id}`);
  }
  w.uvarint(commands.length);
  for (const id of commands) {
    w.uvarint(id);
    w.u8(1); // moveX only
    w.i8(-127);
  }
  return w.finish();
}

function splice(bytes: Uint8Array, at: number, remove: number, insert: Uint8Array): Uint8Array {
  const out = new Uint8Array(bytes.length - remove + insert.length);
  out.set(bytes.subarray(0, at), 0);
  out.set(insert, at);
  out.set(bytes.subarray(at + remove), at + insert.length);
  return out;
}

/** One hostile variant of the log, and what it is. */
function mutate(rng: Prng): { what: string; bytes: Uint8Array } {
  const ticks = entries.filter((e) => e.type === 'tick');
  const victim = rng.pick(ticks);
  const afterHeader = entries[0].offset;
  switch (rng.int(0, 7)) {
    case 0: {
      const bytes = log.slice();
      for (let i = rng.int(1, 3); i > 0; i--) bytes[rng.int(afterHeader, bytes.length - 1)] ^= 1 << rng.int(0, 7);
      return { what: 'flipped bits', bytes };
    }
    case 1:
      return { what: 'cut', bytes: log.slice(0, rng.int(afterHeader, log.length - 1)) };
    case 2: {
      const payload = Uint8Array.from({ length: rng.int(0, 40) }, () => rng.int(0, 255));
      return { what: 'random tick payload', bytes: splice(log, victim.offset, victim.sizeBytes, encodeFrame(RecordType.Tick, payload)) };
    }
    case 3: {
      const type = rng.pick<RecordTypeCode>([RecordType.Header, RecordType.Tick, RecordType.Hash, RecordType.Checkpoint, RecordType.End]);
      const payload = Uint8Array.from({ length: rng.int(0, type === RecordType.Checkpoint ? 400 : 16) }, () => rng.int(0, 255));
      return { what: `inserted random ${type} record`, bytes: splice(log, victim.offset, 0, encodeFrame(type, payload)) };
    }
    case 4: {
      const t = victim.type === 'tick' ? victim.record.tick : 0;
      const present = victim.type === 'tick' ? victim.record.commands.map((c) => c.playerId) : [1];
      const impossible = rng.pick([
        rawTickPayload(t, [], [present[0]], []), // joins a player already in the game
        rawTickPayload(t, [99], [], []), // a player who is not there leaves
        rawTickPayload(t, [], [], [present[0], 4_000_000_000]), // inputs for a stranger
        rawTickPayload(t, [], [2 ** 32], []), // a player id past the log's 32-bit limit
        rawTickPayload(t + 5, [], [], []), // out of sequence
      ]);
      return { what: 'impossible tick record', bytes: splice(log, victim.offset, victim.sizeBytes, encodeFrame(RecordType.Tick, impossible)) };
    }
    case 5: {
      const checkpoint = entries.find((e) => e.type === 'checkpoint')!;
      const bytes = log.slice();
      // Both a divergence (a retouched command) and a checkpoint whose payload is garbage under a valid frame.
      const garbage = Uint8Array.from({ length: checkpoint.sizeBytes - 20 }, () => rng.int(0, 255));
      garbage[0] = 0; // keep the tick counter varint short
      const withGarbage = splice(bytes, checkpoint.offset, checkpoint.sizeBytes, encodeFrame(RecordType.Checkpoint, garbage));
      const retouched = retouchTick(withGarbage, rng.int(1, 8), (rec) => {
        rec.commands[0].input.moveX = rec.commands[0].input.moveX === 127 ? -127 : 127;
      });
      return { what: 'divergence before a garbage checkpoint', bytes: retouched };
    }
    case 6: {
      const bytes = log.slice();
      bytes[rng.int(8, afterHeader - 1)] ^= 0x20; // prelude or header
      return { what: 'damaged header', bytes };
    }
    default:
      return { what: 'intact', bytes: log };
  }
}

describe('replayLog on hostile files', () => {
  it('reports each of 60 hostile logs as ok, diverged or corrupt (with record and offset), or refuses it as no log', async () => {
    const rng = new Prng(0x106);
    const seen = new Set<string>();
    for (let i = 0; i < 60; i++) {
      const { what, bytes } = mutate(rng);
      const path = join(dir, `hostile-${i}.taoslog`);
      await writeFile(path, bytes);
      let outcome: string;
      try {
        const report = await replayLog(path);
        outcome = report.status;
        if (report.status === 'corrupt') {
          expect(report.corruption, what).toMatchObject({ recordIndex: expect.any(Number), byteOffset: expect.any(Number), reason: expect.any(String) });
          expect(report.corruption!.byteOffset, what).toBeLessThan(bytes.length);
        }
        if (report.status === 'diverged') {
          expect(report.divergence?.recordIndex, what).toEqual(expect.any(Number));
          expect(report.divergence?.stateNote, what).toMatch(/^could not compare with a recorded checkpoint: /);
        }
      } catch (error) {
        // Only an unusable prelude or header may refuse the file, with a sentence saying so.
        expect(error instanceof LogFormatError || /cannot be replayed by this build/.test((error as Error).message), `${what}: ${String(error)}`).toBe(true);
        outcome = 'refused';
      }
      seen.add(outcome);
      // The reader alone (what inspect uses) stops only with a LogCorruptError.
      try {
        const reader = await LogReader.open(path);
        try {
          for await (const _ of reader.entries());
        } catch (error) {
          expect(error, what).toBeInstanceOf(LogCorruptError);
        } finally {
          await reader.close();
        }
      } catch (error) {
        if (!(error instanceof LogFormatError)) throw error;
      }
    }
    expect([...seen].sort()).toEqual(['corrupt', 'diverged', 'ok', 'refused']);
  });

  it('names a record the simulation cannot apply, with its index and byte offset', async () => {
    const victim = entries.find((e) => e.type === 'tick' && e.record.tick === 25)!;
    const present = victim.type === 'tick' ? victim.record.commands[0].playerId : 1;
    const bytes = splice(log, victim.offset, victim.sizeBytes, encodeFrame(RecordType.Tick, rawTickPayload(25, [], [present], [])));
    const path = join(dir, 'double-join.taoslog');
    await writeFile(path, bytes);
    const r = await cli('replay', path);
    expect(r.code).toBe(1);
    expect(r.stderr).toMatch(new RegExp(`^CORRUPT LOG at record #${victim.index} \\(byte offset ${victim.offset}\\): the simulation cannot apply tick record 25: .*player ${present} cannot join, it is already in the game\\n {2}the 25 ticks before it replayed`));
  });
});
