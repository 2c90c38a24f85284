// Tests of the CLI on a game's own scenario module (`--scenario ./game.ts`): run is deterministic, record stores
// the module's hash, replay and verify need the module, refuse another version of it clearly, and --force tries.
import { mkdir, mkdtemp, rm } from 'node:fs/promises';
import { tmpdir } from 'node:os';
import { join } from 'node:path';
import { afterAll, beforeAll, describe, expect, it } from 'vitest';
import { LogReader } from '../../server/log/log-reader.ts';
import { moduleSourceHash } from '../../server/scenario-module.ts';
import { cli, jsonOut } from '../helpers/cli.ts';
import { writeGameModule } from '../helpers/game-module.ts';

let dir = '';
let game = '';
let changed = '';
let logPath = '';

beforeAll(async () => {
  dir = await mkdtemp(join(tmpdir(), 'taos-own-scenario-'));
  await mkdir(join(dir, 'v1'));
  await mkdir(join(dir, 'v2'));
  game = await writeGameModule(join(dir, 'v1'));
  changed = await writeGameModule(join(dir, 'v2'), { crateHalfMetres: 0.3 });
  logPath = join(dir, 'session.taoslog');
  const r = await cli('record', '--scenario', game, '--bots', '2', '--ticks', '90', '--out', logPath, '--checkpoint-every', '30');
  if (r.code !== 0) throw new Error(r.stderr);
});
afterAll(async () => {
  await rm(dir, { recursive: true, force: true });
});

describe('--scenario FILE', () => {
  it('run gives the same final hash twice, and another one with another parameter', async () => {
    const a = jsonOut(await cli('run', '--scenario', game, '--ticks', '80', '--bots', '1', '--json'));
    const b = jsonOut(await cli('run', '--scenario', game, '--ticks', '80', '--bots', '1', '--json'));
    const c = jsonOut(await cli('run', '--scenario', game, '--ticks', '80', '--bots', '1', '--param', 'crates=2', '--json'));
    expect(a.scenario).toBe('crate-drop');
    expect(a.hash).toBe(b.hash);
    expect(c.hash).not.toBe(a.hash);
  });

  it('record stores the scenario name, parameters and module hash in the log header', async () => {
    const reader = await LogReader.open(logPath);
    try {
      expect(reader.header).toMatchObject({ formatVersion: 2, scenario: 'crate-drop', scenarioHash: await moduleSourceHash(game) });
    } finally {
      await reader.close();
    }
  });

  it('inspect shows the module hash the log was recorded with', async () => {
    const r = await cli('inspect', logPath);
    expect(r.code).toBe(0);
    expect(r.stdout).toContain(`scenario module: ${await moduleSourceHash(game)}`);
  });

  it('replay with the module reproduces every recorded hash', async () => {
    const r = await cli('replay', logPath, '--scenario', game, '--json');
    expect(r.code).toBe(0);
    expect(jsonOut(r)).toMatchObject({ status: 'ok', scenario: 'crate-drop', ticks: 90 });
  });

  it('replay without the module says the scenario is not built in and how to pass it', async () => {
    const r = await cli('replay', logPath);
    expect(r.code).toBe(1);
    expect(r.stderr).toContain('was recorded with scenario "crate-drop", which is not built in: pass its module with --scenario');
  });

  it('replay with another version of the module refuses and names both hashes; --force replays and reports the divergence', async () => {
    const refused = await cli('replay', logPath, '--scenario', changed);
    expect(refused.code).toBe(1);
    expect(refused.stderr).toMatch(/recorded with another version of scenario "crate-drop" \(module hash sha256:[0-9a-f]{12} in the log, sha256:[0-9a-f]{12} now\): .*pass --force/);
    const forced = await cli('replay', logPath, '--scenario', changed, '--force');
    expect(forced.code).toBe(1);
    expect(forced.stderr).toMatch(/warning: .*another version of scenario "crate-drop".*replaying anyway \(--force\)/);
    expect(forced.stderr).toMatch(/DIVERGED at tick \d+/);
  });

  it('replay with a module of another scenario refuses', async () => {
    const otherDir = join(dir, 'other');
    await mkdir(otherDir);
    const other = await writeGameModule(otherDir, { name: 'ball-drop' });
    const r = await cli('replay', logPath, '--scenario', other);
    expect(r.code).toBe(1);
    expect(r.stderr).toContain('was recorded with scenario "crate-drop", but the module given with --scenario defines "ball-drop"');
  });

  it('verify replays in worker threads with the module and agrees with the log', async () => {
    const r = await cli('verify', logPath, '--scenario', game, '--runs', '2', '--workers', '--json');
    expect(r.code).toBe(0);
    expect(jsonOut(r)).toMatchObject({ agree: true, matchesLog: true, ticks: 90 });
  });

  it('a missing module is a usage error', async () => {
    const r = await cli('run', '--scenario', join(dir, 'missing.ts'));
    expect(r.code).toBe(2);
    expect(r.stderr).toContain('no such scenario module');
  });
});
