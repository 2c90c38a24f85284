// Tests for the access flags of cli/serve-command.ts: mistakes are usage errors (exit 2) before anything
// starts, and a serve process takes its admin token from TAOS_ADMIN_TOKEN, enforces it and never prints it.
import { spawn } from 'node:child_process';
import { join } from 'node:path';
import { afterEach, beforeEach, describe, expect, it } from 'vitest';
import { cli } from '../helpers/cli.ts';

const root = new URL('../../', import.meta.url).pathname;
const TOKEN = 'env-admin-token-0123456789abcdef';
let saved: Record<string, string | undefined> = {};
beforeEach(() => {
  saved = { TAOS_ADMIN_TOKEN: process.env.TAOS_ADMIN_TOKEN, TAOS_JOIN_SECRET: process.env.TAOS_JOIN_SECRET };
  delete process.env.TAOS_ADMIN_TOKEN;
  delete process.env.TAOS_JOIN_SECRET;
});
afterEach(() => {
  for (const [k, v] of Object.entries(saved)) {
    if (v === undefined) delete process.env[k];
    else process.env[k] = v;
  }
});

describe('serve access flags', () => {
  it('exits 2 naming the problem for bad access flags, before starting anything', async () => {
    const cases: Array<[string[], RegExp]> = [
      [['--require-seat'], /--require-seat needs an admin token \(--admin-token or TAOS_ADMIN_TOKEN\)/],
      [['--admin-token', 'short'], /--admin-token must be at least 16 characters/],
      [['--join-secret', 'short'], /--join-secret must be at least 16 characters/],
      [['--allowed-origins', 'game.example'], /"game.example" is not an origin/],
      [['--resume-grace', '-1'], /--resume-grace must be ≥ 0/],
      [['--seat-ttl', '0'], /--seat-ttl must be ≥ 1/],
    ];
    for (const [flags, message] of cases) {
      const r = await cli('serve', '--port', '0', ...flags);
      expect(r.code, flags.join(' ')).toBe(2);
      expect(r.stderr).toMatch(message);
    }
    process.env.TAOS_ADMIN_TOKEN = 'tiny';
    expect((await cli('serve', '--port', '0')).stderr).toMatch(/TAOS_ADMIN_TOKEN must be at least 16 characters/);
  });

  it('reads the admin token from TAOS_ADMIN_TOKEN, requires it on operator routes, and never prints it', async () => {
    const child = spawn(join(root, 'node_modules/.bin/node'), [join(root, 'bin/taos-physics.js'), 'serve', '--port', '0', '--require-seat', '--scenario', 'pendulum-chain'], {
      cwd: root,
      stdio: ['ignore', 'pipe', 'pipe'],
      env: { ...process.env, VITEST: '', TAOS_ADMIN_TOKEN: TOKEN },
    });
    let stdout = '';
    let stderr = '';
    child.stdout.on('data', (d: Buffer) => (stdout += d.toString()));
    child.stderr.on('data', (d: Buffer) => (stderr += d.toString()));
    const exited = new Promise<number | null>((resolve) => child.on('exit', (code) => resolve(code)));
    try {
      const deadline = performance.now() + 15_000;
      while (!/http:\/\/\S+\//.test(stdout)) {
        if (performance.now() > deadline) throw new Error(`no URL printed; stderr: ${stderr}`);
        await new Promise((r) => setTimeout(r, 20));
      }
      const url = /(http:\/\/\S+\/) /.exec(stdout)![1];
      expect((await fetch(`${url}metrics`)).status).toBe(401);
      expect((await fetch(`${url}metrics`, { headers: { authorization: `Bearer ${TOKEN}` } })).status).toBe(200);
      const seat = await fetch(`${url}api/rooms/default/seats`, { method: 'POST', headers: { authorization: `Bearer ${TOKEN}` } });
      expect(seat.status).toBe(201);
      child.kill('SIGTERM');
      expect(await exited).toBe(0);
      const lines = stderr.trim().split('\n').map((l) => JSON.parse(l) as Record<string, unknown>);
      expect(lines.find((l) => l.msg === 'access control')).toMatchObject({ adminToken: true, requireSeat: true, allowedOrigins: 'self,loopback', joinSecret: 'random per process' });
      expect(stdout + stderr).not.toContain(TOKEN);
    } finally {
      if (child.exitCode === null) child.kill('SIGKILL');
    }
  });
});
