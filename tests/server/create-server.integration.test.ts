// Integration test of server/create-server.ts: a server made in code from a game's own scenario (a module path or a
// loaded definition) serves it to WebSocket players and records logs that carry the module's hash and replay.
import { mkdtemp, readdir, rm } from 'node:fs/promises';
import { tmpdir } from 'node:os';
import { join } from 'node:path';
import { afterAll, beforeAll, describe, expect, it } from 'vitest';
import { replayLog } from '../../cli/replay-session.ts';
import { createServer } from '../../server/create-server.ts';
import { silentLogger } from '../../server/logger.ts';
import { loadScenarioModule, moduleSourceHash } from '../../server/scenario-module.ts';
import { writeGameModule } from '../helpers/game-module.ts';
import { WsTestClient } from './ws-client.ts';

let dir = '';
let game = '';
beforeAll(async () => {
  dir = await mkdtemp(join(tmpdir(), 'taos-create-server-'));
  game = await writeGameModule(dir);
});
afterAll(async () => {
  await rm(dir, { recursive: true, force: true });
});

describe('createServer', () => {
  it('serves a scenario module to players and records a log with its hash that replays', async () => {
    const recordDir = join(dir, 'rec');
    const server = await createServer({ port: 0, scenarios: [game], recordDir, logger: silentLogger() });
    try {
      const a = await WsTestClient.join(server.wsUrl, 'ann');
      const b = await WsTestClient.join(server.wsUrl, 'bob');
      expect(a.welcome!.scenario.name).toBe('crate-drop');
      await a.waitFor(() => a.frames.length > 5 && b.frames.length > 5, 10_000, 'snapshots');
      a.close();
      b.close();
    } finally {
      await server.close();
    }
    const [file] = await readdir(recordDir);
    const report = await replayLog(join(recordDir, file), { scenario: await loadScenarioModule(game) });
    expect(report.header).toMatchObject({ scenario: 'crate-drop', scenarioHash: await moduleSourceHash(game) });
    expect(report.status).toBe('ok');
    expect(report.hashesChecked).toBeGreaterThan(0);
  });

  it('runs a definition in a room worker, which loads the module that defined it, and records its hash', async () => {
    const recordDir = join(dir, 'rec-worker');
    const def = await loadScenarioModule(game);
    const server = await createServer({ port: 0, scenarios: [def], roomWorkers: 1, recordDir, logger: silentLogger() });
    try {
      const a = await WsTestClient.join(server.wsUrl, 'ann');
      expect(a.welcome!.scenario.name).toBe('crate-drop');
      await a.waitFor(() => a.frames.length > 5, 10_000, 'snapshots');
      a.close();
    } finally {
      await server.close();
    }
    const [file] = await readdir(recordDir);
    const report = await replayLog(join(recordDir, file), { scenario: def });
    expect(report.header.scenarioHash).toBe(await moduleSourceHash(game));
    expect(report.status).toBe('ok');
  });

  it('refuses a definition whose module is unknown when rooms run in workers', async () => {
    const bare = { ...(await loadScenarioModule(game)) }; // a copy: no longer the module's defineScenario result
    await expect(createServer({ port: 0, scenarios: [{ ...bare, name: 'plain' }], roomWorkers: 1, logger: silentLogger() })).rejects.toThrow(/the module of scenario "plain" is unknown/);
  });

  it('takes loaded definitions, offers only the given scenarios, and refuses an empty list or duplicate names', async () => {
    const def = await loadScenarioModule(game);
    const server = await createServer({ port: 0, scenarios: [def], logger: silentLogger() });
    try {
      const res = await fetch(new URL('/api/scenarios', server.url));
      const body = (await res.json()) as { scenarios: Array<{ name: string }> };
      expect(body.scenarios.map((s) => s.name)).toEqual(['crate-drop']);
    } finally {
      await server.close();
    }
    await expect(createServer({ port: 0, scenarios: [], logger: silentLogger() })).rejects.toThrow('createServer: scenarios must be a non-empty array');
    await expect(createServer({ port: 0, scenarios: [def, def], logger: silentLogger() })).rejects.toThrow('scenarios: two scenarios are called "crate-drop"');
  });
});
