// Integration test for cli/serve.ts through the real CLI process: `serve --port 0 --record DIR` prints its URL,
// plays over WebSocket, and on SIGTERM tells clients why, ends the recording (which replays) and exits 0.
import { spawn } from 'node:child_process';
import { mkdtempSync, readdirSync, rmSync } from 'node:fs';
import { tmpdir } from 'node:os';
import { join } from 'node:path';
import { afterAll, describe, expect, it } from 'vitest';
import { replayLog } from '../../cli/replay-session.ts';
import { ByeReason } from '../../shared/protocol/index.ts';
import { NEUTRAL_INPUT } from '../../shared/sim/input.ts';
import { WsTestClient } from '../server/ws-client.ts';

const tmp = mkdtempSync(join(tmpdir(), 'taos-serve-'));
afterAll(() => rmSync(tmp, { recursive: true, force: true }));
const root = new URL('../../', import.meta.url).pathname;

describe('serve (CLI process)', () => {
  it('shuts down on SIGTERM: byes with the reason, a complete recording that replays, logs flushed, exit 0', async () => {
    const dir = join(tmp, 'rec');
    const child = spawn(join(root, 'node_modules/.bin/node'), [join(root, 'bin/taos-physics.js'), 'serve', '--port', '0', '--record', dir, '--param', 'crateRows=2'], {
      cwd: root,
      stdio: ['ignore', 'pipe', 'pipe'],
      env: { ...process.env, VITEST: '' },
    });
    let stdout = '';
    let stderr = '';
    child.stdout.on('data', (d: Buffer) => (stdout += d.toString()));
    child.stderr.on('data', (d: Buffer) => (stderr += d.toString()));
    const exited = new Promise<number | null>((resolve) => child.on('exit', (code) => resolve(code)));
    try {
      const deadline = performance.now() + 15_000;
      while (!/ws:\/\/\S+\//.test(stdout)) {
        if (performance.now() > deadline) throw new Error(`no URL printed; stderr: ${stderr}`);
        await new Promise((r) => setTimeout(r, 20));
      }
      const wsUrl = /(ws:\/\/\S+\/)/.exec(stdout)![1];
      const a = await WsTestClient.join(wsUrl, 'ann');
      const b = await WsTestClient.join(wsUrl, 'bob');
      const timer = setInterval(() => {
        const tick = (a.frames.at(-1)?.tick ?? 0) + 5;
        a.send({ type: 'input', firstTick: tick, commands: [{ ...NEUTRAL_INPUT, moveZ: 127 }] });
        b.send({ type: 'input', firstTick: tick, commands: [{ ...NEUTRAL_INPUT, moveX: 127, buttons: 2 }] });
      }, 16);
      await a.waitFor(() => (a.frames.at(-1)?.tick ?? 0) > 120, 10_000, '120 ticks');
      clearInterval(timer);
      child.kill('SIGTERM');
      expect(await exited).toBe(0);
      await a.waitFor(() => a.closed !== null && b.closed !== null, 3000, 'sockets closed');
      expect(a.ofType('bye')[0]).toMatchObject({ reason: ByeReason.ServerShutdown, message: 'server shutting down (SIGTERM)' });
      expect(b.ofType('bye')[0]?.reason).toBe(ByeReason.ServerShutdown);
      const lines = stderr.trim().split('\n').map((l) => JSON.parse(l) as { msg: string });
      expect(lines.map((l) => l.msg)).toEqual(expect.arrayContaining(['recording room', 'player joined', 'shutting down', 'recording complete', 'shutdown complete']));
      const files = readdirSync(dir).filter((f) => f.endsWith('.taoslog')); // resume keys sit beside each log
      expect(files).toHaveLength(1);
      const report = await replayLog(join(dir, files[0]));
      expect(report).toMatchObject({ status: 'ok', log: 'complete' });
      expect(report.ticks).toBeGreaterThan(120);
      expect(report.header.params.crateRows).toBe(2);
    } finally {
      if (child.exitCode === null) child.kill('SIGKILL');
    }
  });
});
