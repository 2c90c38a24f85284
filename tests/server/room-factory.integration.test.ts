// Rooms give everything back when they close: 50 open/close cycles on a real server (every other room with two
// WebSocket players in it) leave Node's external memory and RSS flat. Measured in a child process with --expose-gc
// (tests/server/room-churn-probe.ts) so that nothing else in the test worker moves the numbers.
import { spawn } from 'node:child_process';
import { fileURLToPath } from 'node:url';
import { describe, expect, it } from 'vitest';

const PROBE = fileURLToPath(new URL('./room-churn-probe.ts', import.meta.url));

interface Memory {
  externalBytes: number;
  rssBytes: number;
}

function runProbe(args: string[]): Promise<{ before: Memory; after: Memory; trace: Array<Memory & { cycle: number }> }> {
  // A 4 MiB young generation: V8 otherwise grows its semi-spaces towards 64 MiB under the allocation rate of module
  // start-ups, a one-off RSS rise unrelated to rooms (reproduced with bare instantiations, no rooms at all).
  const child = spawn(process.execPath, ['--expose-gc', '--max-semi-space-size=4', PROBE, ...args], { stdio: ['ignore', 'pipe', 'pipe'] });
  let out = '';
  let err = '';
  child.stdout.on('data', (d: Buffer) => (out += d.toString('utf8')));
  child.stderr.on('data', (d: Buffer) => (err += d.toString('utf8')));
  return new Promise((resolve, reject) => {
    const timer = setTimeout(() => child.kill('SIGKILL'), 170_000);
    child.on('exit', (code) => {
      clearTimeout(timer);
      if (code !== 0) reject(new Error(`room-churn probe exited with ${code}: ${err.slice(-2000)}`));
      else resolve(JSON.parse(out.trim().split('\n').at(-1)!));
    });
  });
}

const MiB = 1024 * 1024;

describe('room-factory on a live server', () => {
  it('keeps external memory and RSS within 5% over 50 room open/close cycles, half of them with players', async () => {
    const r = await runProbe(['--cycles', '50', '--warmup', '30']);
    const show = (m: Memory): string => `external ${(m.externalBytes / MiB).toFixed(1)} MiB, RSS ${(m.rssBytes / MiB).toFixed(1)} MiB`;
    const detail = `before: ${show(r.before)}; after: ${show(r.after)}; every 5 cycles: ${r.trace.map(show).join(' | ')}`;
    // One retained room alone would add its 128 MiB heap to external memory: 20 times the allowance.
    expect(r.after.externalBytes / r.before.externalBytes, detail).toBeLessThan(1.05);
    expect(r.after.externalBytes / r.before.externalBytes, detail).toBeGreaterThan(0.95);
    expect(r.after.rssBytes / r.before.rssBytes, detail).toBeLessThan(1.05);
    expect(r.after.rssBytes / r.before.rssBytes, detail).toBeGreaterThan(0.95);
  }, 180_000);
});
