// Fuzz test of the whole server process on loopback: at least FUZZ_FRAMES (default 100,000) generated hostile frames
// from short-lived sockets, while two honest players (the client library, from 127.0.0.1) play and every room
// records. The process must stay up and never hit an internal error, the honest players must never be disconnected,
// and every recording must replay exactly. FUZZ_SEED replays a run's frames (the seed is printed); a long run:
// FUZZ_FRAMES=2000000 npx vitest run tests/server/fuzz.integration.test.ts
import { spawn, type ChildProcess } from 'node:child_process';
import { mkdtempSync, readdirSync, rmSync } from 'node:fs';
import { tmpdir } from 'node:os';
import { join } from 'node:path';
import { afterAll, describe, expect, it } from 'vitest';
import { connect, type NetClient } from '../../sdk/index.ts';
import { replayLog } from '../../cli/replay-session.ts';
import { ByeReason } from '../../shared/protocol/index.ts';
import { quantizeInput } from '../../shared/sim/input.ts';
import { Prng } from '../../shared/sim/prng.ts';
import { canBindLoopbackRange, framesThatThrow, runFuzz, type FuzzStats } from '../helpers/fuzz-driver.ts';
import { FRAME_KINDS } from '../helpers/hostile-frames.ts';

const FRAMES = Number(process.env.FUZZ_FRAMES ?? 100_000);
const SEED = process.env.FUZZ_SEED !== undefined ? Number(process.env.FUZZ_SEED) >>> 0 : (Date.now() ^ (process.pid << 16)) >>> 0;
const LANES = 24;
/** Generous: about a minute on an idle 2-core machine; the deadline only turns a hang into a clear failure. */
const DEADLINE_MS = Math.max(240_000, FRAMES * 2);

const root = new URL('../../', import.meta.url).pathname;
const tmp = mkdtempSync(join(tmpdir(), 'taos-fuzz-'));
afterAll(() => rmSync(tmp, { recursive: true, force: true }));

interface ServerProcess {
  child: ChildProcess;
  wsUrl: string;
  httpUrl: string;
  stderr: () => string;
  exited: Promise<number | null>;
}

async function startServe(recordDir: string): Promise<ServerProcess> {
  const child = spawn(join(root, 'node_modules/.bin/node'), [join(root, 'bin/taos-physics.js'), 'serve', '--port', '0', '--record', recordDir, '--param', 'crateRows=1', '--log-level', 'warn'], {
    cwd: root,
    stdio: ['ignore', 'pipe', 'pipe'],
    env: { ...process.env, VITEST: '', TAOS_LOG_LEVEL: '' },
  });
  let stdout = '';
  let stderr = '';
  child.stdout!.on('data', (d: Buffer) => (stdout += d.toString()));
  child.stderr!.on('data', (d: Buffer) => (stderr += d.toString()));
  const exited = new Promise<number | null>((resolve) => child.on('exit', (code) => resolve(code)));
  const deadline = performance.now() + 30_000;
  while (!/ws:\/\/\S+\//.test(stdout)) {
    if (performance.now() > deadline || child.exitCode !== null) throw new Error(`serve printed no URL; stderr: ${stderr}`);
    await new Promise((r) => setTimeout(r, 20));
  }
  const wsUrl = /(ws:\/\/\S+\/)/.exec(stdout)![1];
  return { child, wsUrl, httpUrl: wsUrl.replace('ws://', 'http://'), stderr: () => stderr, exited };
}

/** An honest player: the client library, inputs every 50 ms, every way of losing it recorded. */
function honestPlayer(url: string, name: string, rng: Prng): { client: NetClient; problems: string[]; snapshots: () => number; stop: () => void } {
  const client = connect(url, { name, reconnect: false });
  const problems: string[] = [];
  let snapshots = 0;
  client.on('snapshot', () => snapshots++);
  client.on('reconnecting', (r) => problems.push(`reconnecting: ${r.reason}`));
  client.on('closed', (c) => problems.push(`closed: ${c.reason}: ${c.detail}`));
  client.on('bye', (b) => problems.push(`bye: ${b.reason}: ${b.message}`));
  client.on('serverError', (e) => problems.push(`server error: ${e.code}: ${e.message}`));
  client.on('protocolError', (m) => problems.push(`protocol error: ${m}`));
  const timer = setInterval(() => {
    if (client.state === 'connected') client.setInput(quantizeInput(rng.range(-1, 1), rng.range(-1, 1), rng.range(0, 6.28), rng.range(-1, 1), rng.int(0, 15)));
  }, 50);
  return { client, problems, snapshots: () => snapshots, stop: () => clearInterval(timer) };
}

/** The sum of a Prometheus counter's samples in /metrics text (0 when it has none). */
function counterSum(text: string, name: string): number {
  let sum = 0;
  for (const line of text.split('\n')) if (line.startsWith(`${name} `) || line.startsWith(`${name}{`)) sum += Number(line.slice(line.lastIndexOf(' ') + 1));
  return sum;
}

function describeRun(stats: FuzzStats): string {
  const fps = Math.round(stats.generatedFrames / stats.seconds);
  return (
    `fuzz seed ${SEED}: ${stats.generatedFrames} generated frames (+${stats.fillerFrames} valid filler) in ${stats.seconds.toFixed(1)} s = ${fps} frames/s; ` +
    `${stats.sockets} sockets (${stats.socketsRefused} refused), ${stats.rawTcpConnections} raw TCP; frames by kind ${JSON.stringify(stats.byKind)}; ` +
    `byes to fuzzers ${JSON.stringify(stats.byeReasons)}; errors ${JSON.stringify(stats.errorCodes)}`
  );
}

describe('fuzz (real server process)', () => {
  it(`survives ${FRAMES} generated hostile frames while two honest players play and the rooms record`, { timeout: DEADLINE_MS + 120_000 }, async () => {
    const recordDir = join(tmp, 'rec');
    const server = await startServe(recordDir);
    const rng = new Prng(SEED);
    try {
      const honest = [honestPlayer(server.wsUrl, 'honest-ann', rng), honestPlayer(server.wsUrl, 'honest-bob', rng)];
      await Promise.all(honest.map((h) => h.client.whenConnected()));
      const spreadAddresses = await canBindLoopbackRange(Number(new URL(server.httpUrl).port));
      const before = honest.map((h) => h.snapshots());
      const stats = await runFuzz({ url: server.wsUrl, seed: SEED, frames: FRAMES, lanes: LANES, deadlineMs: DEADLINE_MS, spreadAddresses });
      console.log(describeRun(stats));
      await new Promise((r) => setTimeout(r, 500)); // the last answers and leaves settle

      // The process is alive and answering, and nothing it handled failed inside. When something did, the frames
      // that make the decoder throw here are the first suspects (the seed regenerates them all).
      const alive = server.child.exitCode === null;
      const metrics = alive ? await (await fetch(`${server.httpUrl}metrics`)).text() : '';
      const failures = alive ? counterSum(metrics, 'taos_message_errors_total') + counterSum(metrics, 'taos_uncaught_errors_total') : 1;
      const suspects = failures > 0 || stats.incidents.length > 0 ? framesThatThrow(stats.frameLog) : [];
      const context = `seed ${SEED}; frames that throw in the decoder: ${suspects.join(', ') || 'none'}; server stderr:\n${server.stderr().slice(-3000)}`;
      expect(alive, `the server exited during the fuzz: ${context}`).toBe(true);
      console.log(`server: ${counterSum(metrics, 'taos_messages_received_total')} messages received, disconnects ${metrics.split('\n').filter((l) => l.startsWith('taos_disconnects_total{')).map((l) => l.replace('taos_disconnects_total', '')).join(' ')}`);
      expect(stats.incidents.slice(0, 3), `internal errors answered to fuzz sockets (their recent frames in hex): ${context}`).toEqual([]);
      expect(failures, `message or uncaught errors in the server: ${context}`).toBe(0);
      // Fuzz sockets are sent away only for what they did (and a bye is all a healthy server ever kicks with).
      const expectedByes = new Set<string>([ByeReason.TooManyErrors, ByeReason.Flood, ByeReason.VersionMismatch, ByeReason.RoomNotFound, ByeReason.RoomFull, ByeReason.ServerFull, ByeReason.Timeout]);
      expect(Object.keys(stats.byeReasons).filter((r) => !expectedByes.has(r)), context).toEqual([]);
      expect(stats.timedOut, `only ${stats.generatedFrames} frames before the deadline`).toBe(false);
      expect(stats.generatedFrames).toBeGreaterThanOrEqual(FRAMES);
      if (FRAMES >= 10_000) expect(Object.keys(stats.byKind).sort()).toEqual([...FRAME_KINDS].sort());

      // The honest players never noticed: connected all along, snapshots kept coming.
      for (const [i, h] of honest.entries()) {
        expect(h.problems, `honest player ${i} (seed ${SEED})`).toEqual([]);
        expect(h.client.state).toBe('connected');
        expect(h.client.stats().reconnects).toBe(0);
        expect(h.snapshots() - before[i]).toBeGreaterThan(60); // it kept playing all along (no slow-down test here)
      }
      for (const h of honest) {
        h.stop();
        h.client.close();
      }
      await new Promise((r) => setTimeout(r, 100));
      server.child.kill('SIGTERM');
      expect(await server.exited).toBe(0);
      const errorLines = server
        .stderr()
        .split('\n')
        .filter((l) => l.startsWith('{'))
        .map((l) => JSON.parse(l) as { level: number; msg: string })
        .filter((l) => l.level >= 50);
      expect(errorLines, `seed ${SEED}`).toEqual([]);

      // Every room's recording replays exactly, with the fuzzers' joins, leaves and inputs in it.
      const files = readdirSync(recordDir).filter((f) => f.endsWith('.taoslog')); // resume keys sit beside each log
      expect(files.length).toBeGreaterThanOrEqual(1);
      for (const file of files) {
        const report = await replayLog(join(recordDir, file));
        expect(report.status, `${file} (seed ${SEED}): ${JSON.stringify(report.divergence ?? report.corruption)}`).toBe('ok');
        expect(report.log).toBe('complete');
      }
    } finally {
      if (server.child.exitCode === null) server.child.kill('SIGKILL');
    }
  });
});
