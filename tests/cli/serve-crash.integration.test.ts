// Crash test of issue 13 through real processes: scripted bots (the client library over loopback WebSockets) play a
// recorded room, the server is killed with SIGKILL at a seeded random moment, restarted with --resume on the same
// port, and the bots come back on their own. Then: no tick any bot saw is missing from the log, the resumed state
// equals the hash recorded at the resume tick, the bots keep their players, and the whole session replays.
import { spawn, type ChildProcess } from 'node:child_process';
import { copyFileSync, mkdtempSync, readdirSync, readFileSync, rmSync } from 'node:fs';
import { tmpdir } from 'node:os';
import { join } from 'node:path';
import { afterAll, describe, expect, it } from 'vitest';
import { replayLog } from '../../cli/replay-session.ts';
import { readLogBytes } from '../../server/log/log-bytes.ts';
import { connect, type NetClient } from '../../sdk/client.ts';
import { NEUTRAL_INPUT } from '../../shared/sim/input.ts';

const tmp = mkdtempSync(join(tmpdir(), 'taos-crash-'));
afterAll(() => rmSync(tmp, { recursive: true, force: true }));
const root = new URL('../../', import.meta.url).pathname;

interface Serve {
  child: ChildProcess;
  stdout(): string;
  stderr(): string;
  exited: Promise<number | null>;
}

function serve(args: string[]): Serve {
  const child = spawn(join(root, 'node_modules/.bin/node'), [join(root, 'bin/taos-physics.js'), 'serve', '--log-level', 'warn', ...args], { cwd: root, stdio: ['ignore', 'pipe', 'pipe'], env: { ...process.env, VITEST: '' } });
  let out = '';
  let err = '';
  child.stdout!.on('data', (d: Buffer) => (out += d.toString()));
  child.stderr!.on('data', (d: Buffer) => (err += d.toString()));
  return { child, stdout: () => out, stderr: () => err, exited: new Promise((resolve) => child.on('exit', (code) => resolve(code))) };
}

async function waitFor(what: string, cond: () => boolean, timeoutMs: number): Promise<void> {
  const end = performance.now() + timeoutMs;
  while (!cond()) {
    if (performance.now() > end) throw new Error(`timed out after ${timeoutMs} ms waiting for ${what}`);
    await new Promise((r) => setTimeout(r, 10));
  }
}

/** A bot: the client library with a seeded walk, remembering every tick it saw applied (snapshots and events). */
class Bot {
  readonly client: NetClient;
  maxSeenTick = -1;
  welcomes: Array<{ playerId: number; resumed: boolean; tick: number }> = [];
  restartNoticed = false;
  private rng: number;
  constructor(url: string, name: string, seed: number) {
    this.rng = seed;
    this.client = connect(url, { name, reconnect: { baseDelayMs: 100, maxDelayMs: 500, maxAttempts: 60 } });
    this.client.on('welcome', (w) => this.welcomes.push({ playerId: w.playerId, resumed: w.resumed, tick: w.tick }));
    this.client.on('snapshot', (s) => (this.maxSeenTick = Math.max(this.maxSeenTick, s.tick)));
    this.client.on('events', (events) => {
      for (const e of events) this.maxSeenTick = Math.max(this.maxSeenTick, e.tick);
    });
    this.client.on('reconnecting', (r) => (this.restartNoticed ||= r.serverRestarting));
  }
  /** A new seeded command (a linear congruential step: test-side randomness, not the simulation's). */
  steer(): void {
    this.rng = (this.rng * 1103515245 + 12345) % 2147483648;
    const r = this.rng / 2147483648;
    if (this.client.state === 'connected') this.client.setInput({ ...NEUTRAL_INPUT, moveX: Math.round(r * 254) - 127, moveZ: 127, yaw: Math.floor(r * 65535), buttons: r > 0.8 ? 1 : 0 });
  }
}

const recordedTicks = (bytes: Uint8Array): number => readLogBytes(bytes).outcome.ticks;
const hashRecordAt = (bytes: Uint8Array, tick: number): string | undefined => readLogBytes(bytes).entries.flatMap((e) => (e.type === 'hash' && e.tick === tick ? [e.hash] : []))[0];

describe('serve --resume after kill -9 (CLI processes)', () => {
  for (const seed of [1, 2, 3]) {
    it(`loses no tick a bot saw, resumes at the recorded state, and the bots keep playing (seed ${seed})`, async () => {
      const dir = join(tmp, `s${seed}`);
      const common = ['--hash-every', '1', '--checkpoint-every', '1', '--durability', 'tick'];
      let first: Serve | null = serve(['--port', '0', '--record', dir, ...common]);
      let second: Serve | null = null;
      const bots: Bot[] = [];
      const steer = setInterval(() => bots.forEach((b) => b.steer()), 50);
      try {
        await waitFor('the first server', () => /ws:\/\/\S+\//.test(first!.stdout()), 20_000);
        const wsUrl = /(ws:\/\/\S+\/)/.exec(first.stdout())![1];
        const port = /:(\d+)\/$/.exec(wsUrl)![1];
        bots.push(new Bot(wsUrl, 'ann', seed * 7), new Bot(wsUrl, 'bob', seed * 13));
        await waitFor('both welcomes', () => bots.every((b) => b.welcomes.length === 1), 10_000);
        // The kill lands at a seeded random moment between 0.5 and 2 s of play.
        const playMs = 500 + ((seed * 7919) % 1500);
        await new Promise((r) => setTimeout(r, playMs));
        first.child.kill('SIGKILL');
        await first.exited;
        first = null;
        const seen = Math.max(...bots.map((b) => b.maxSeenTick));
        expect(seen).toBeGreaterThan(0);
        const files = readdirSync(dir).filter((f) => f.endsWith('.taoslog'));
        expect(files).toHaveLength(1);
        const logPath = join(dir, files[0]);
        copyFileSync(logPath, join(tmp, `s${seed}-before.taoslog`));
        const before = new Uint8Array(readFileSync(logPath));
        // 0 ticks any client saw applied are missing: tick record `seen` is in the log.
        expect(recordedTicks(before)).toBeGreaterThan(seen);

        second = serve(['--port', port, '--resume', dir, ...common]);
        await waitFor('the resumed server', () => /serving/.test(second!.stdout()), 20_000);
        const resumed = /resumed room default at tick (\d+) \(hash ([0-9a-f]{16}), 2 player\(s\) held\)/.exec(second.stdout());
        expect(resumed, second.stdout() + second.stderr()).not.toBeNull();
        const resumeTick = Number(resumed![1]);
        expect(resumeTick).toBe(recordedTicks(before));
        expect(resumed![2]).toBe(hashRecordAt(before, resumeTick));

        // The bots come back by themselves with their own players, and play on past the resume tick.
        await waitFor('both bots back', () => bots.every((b) => b.welcomes.length === 2), 20_000);
        for (const b of bots) {
          expect(b.welcomes[1]).toMatchObject({ playerId: b.welcomes[0].playerId, resumed: true });
          expect(b.restartNoticed).toBe(true);
        }
        await waitFor('play after the resume', () => bots.every((b) => b.maxSeenTick > resumeTick + 30), 10_000);

        second.child.kill('SIGTERM');
        expect(await second.exited).toBe(0);
        second = null;
        const report = await replayLog(logPath);
        expect(report).toMatchObject({ status: 'ok', log: 'complete' });
        expect(report.ticks).toBeGreaterThan(resumeTick + 30);
        expect(report.hashesChecked).toBe(report.ticks + 2); // every tick's hash, the initial one and the end record
        const entries = readLogBytes(new Uint8Array(readFileSync(logPath))).entries;
        // The drain on SIGTERM wrote a last checkpoint at the final tick, then the end record.
        expect(entries.slice(-2).map((e) => [e.type, 'tick' in e ? e.tick : null])).toEqual([['checkpoint', report.ticks], ['end', report.ticks]]);
        const records = entries.flatMap((e) => (e.type === 'tick' ? [e.record] : []));
        const ids = bots.map((b) => b.welcomes[0].playerId);
        expect(records.flatMap((r) => r.joins.map((j) => j.playerId)).filter((id) => ids.includes(id))).toEqual(ids.slice().sort((a, b) => a - b));
        expect(records.flatMap((r) => r.leaves).filter((id) => ids.includes(id))).toEqual([]);
      } finally {
        clearInterval(steer);
        for (const b of bots) b.client.close();
        first?.child.kill('SIGKILL');
        second?.child.kill('SIGKILL');
      }
    }, 90_000);
  }
});
