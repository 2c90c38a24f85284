// Tests for `record`: the log holds the bots' exact inputs and the simulation's hashes and checkpoints, the same
// command writes the same bytes, and existing files are never replaced without --force.
import '../../server/physics-node.ts';
import { mkdtemp, readFile, rm, writeFile } from 'node:fs/promises';
import { tmpdir } from 'node:os';
import { join } from 'node:path';
import { afterAll, beforeAll, describe, expect, it } from 'vitest';
import { readLogBytes } from '../../server/log/log-bytes.ts';
import { getScenario } from '../../scenarios/index.ts';
import { BotScript } from '../../shared/sim/bots.ts';
import { Simulation } from '../../shared/sim/simulation.ts';
import { cli, jsonOut } from '../helpers/cli.ts';

let dir = '';
beforeAll(async () => {
  dir = await mkdtemp(join(tmpdir(), 'taos-record-'));
});
afterAll(async () => {
  await rm(dir, { recursive: true, force: true });
});

describe('record-command', () => {
  it('writes the bots\' inputs, a hash per tick, checkpoints and an end record matching an independent run', async () => {
    const out = join(dir, 'course.taoslog');
    const r = await cli('record', '--scenario', 'character-course', '--bots', '3', '--ticks', '90', '--out', out, '--seed', '11', '--checkpoint-every', '30', '--param', 'crateRows=2', '--json');
    expect(r.code).toBe(0);
    const summary = jsonOut(r);
    const { header, entries, outcome } = readLogBytes(await readFile(out));
    expect(outcome.status).toBe('complete');
    expect(summary).toMatchObject({ file: out, scenario: 'character-course', ticks: 90, bots: 3, sizeBytes: outcome.fileBytes });
    expect(header).toMatchObject({ scenario: 'character-course', seed: 11, tickRateHz: 60, hashEveryTicks: 1, checkpointEveryTicks: 30, joltVersion: '1.1.0' });
    expect(header.params.crateRows).toBe(2);
    expect(Object.keys(header.params).length).toBeGreaterThan(1); // every resolved parameter, not just the given one

    const sim = await Simulation.create({ scenario: getScenario('character-course'), params: { crateRows: 2 }, seed: 11 });
    const bots = new BotScript({ seed: 11, bots: 3 });
    const expected: unknown[] = [{ type: 'hash', tick: 0, hash: sim.stateHash() }];
    for (let t = 0; t < 90; t++) {
      const record = bots.next();
      sim.step(record);
      expected.push({ type: 'tick', record });
      expected.push({ type: 'hash', tick: t + 1, hash: sim.stateHash() });
      if ((t + 1) % 30 === 0) expected.push({ type: 'checkpoint', tick: t + 1 });
    }
    expected.push({ type: 'end', tick: 90, hash: sim.stateHash() });
    sim.destroy();
    expect(entries.map((e) => (e.type === 'checkpoint' ? { type: e.type, tick: e.tick } : e.type === 'tick' ? { type: e.type, record: e.record } : { type: e.type, tick: e.tick, hash: e.hash }))).toEqual(expected);
    expect(entries.filter((e) => e.type === 'tick').some((e) => e.type === 'tick' && e.record.commands.some((c) => c.input.buttons !== 0))).toBe(true);
    expect(summary.hash).toBe((expected.at(-1) as { hash: string }).hash);
  });

  it('writes byte-identical logs for the same command line', async () => {
    const a = join(dir, 'same-a.taoslog');
    const b = join(dir, 'same-b.taoslog');
    for (const out of [a, b]) expect((await cli('record', '--scenario', 'character-course', '--bots', '2', '--ticks', '30', '--out', out)).code).toBe(0);
    expect(Buffer.compare(await readFile(a), await readFile(b))).toBe(0);
  });

  it('refuses to replace an existing file unless --force is given', async () => {
    const out = join(dir, 'keep.taoslog');
    await writeFile(out, 'important');
    const r = await cli('record', '--scenario', 'character-course', '--bots', '1', '--ticks', '5', '--out', out);
    expect(r.code).toBe(2);
    expect(r.stderr).toContain(`${out} already exists (pass --force to replace it)`);
    expect(await readFile(out, 'utf8')).toBe('important');
    expect((await cli('record', '--scenario', 'character-course', '--bots', '1', '--ticks', '5', '--out', out, '--force')).code).toBe(0);
    expect(readLogBytes(await readFile(out)).outcome.status).toBe('complete');
  });

  it('honours --hash-every and --checkpoint-every 0', async () => {
    const out = join(dir, 'sparse.taoslog');
    expect((await cli('record', '--scenario', 'character-course', '--bots', '1', '--ticks', '25', '--out', out, '--hash-every', '10', '--checkpoint-every', '0')).code).toBe(0);
    const { entries } = readLogBytes(await readFile(out));
    expect(entries.filter((e) => e.type === 'hash').map((e) => (e.type === 'hash' ? e.tick : -1))).toEqual([0, 10, 20]);
    expect(entries.some((e) => e.type === 'checkpoint')).toBe(false);
  });
});
