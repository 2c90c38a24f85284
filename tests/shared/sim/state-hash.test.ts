// Tests of the 64-bit state hash: its mixing properties, and that one session hashes identically tick by tick in
// this process, in two child processes and in two worker threads.
import { spawn } from 'node:child_process';
import { fileURLToPath } from 'node:url';
import { Worker } from 'node:worker_threads';
import { describe, expect, it } from 'vitest';
import { Hasher64, hashWords } from '../../../shared/sim/state-hash.ts';
import { botRecords, makeSim, runHashes } from './helpers/sim-helpers.ts';

const RUNNER = fileURLToPath(new URL('./helpers/hash-runner.ts', import.meta.url));
const TICKS = 120;

function inChildProcess(): Promise<string[]> {
  return new Promise((resolve, reject) => {
    const child = spawn(process.execPath, [RUNNER, String(TICKS)], { stdio: ['ignore', 'pipe', 'pipe'] });
    let out = '';
    let err = '';
    child.stdout.on('data', (d) => (out += d));
    child.stderr.on('data', (d) => (err += d));
    const timer = setTimeout(() => child.kill(), 30_000);
    child.on('close', (code) => {
      clearTimeout(timer);
      if (code !== 0) reject(new Error(`runner exited ${code}: ${err}`));
      else resolve(JSON.parse(out) as string[]);
    });
  });
}

function inWorker(): Promise<string[]> {
  return new Promise((resolve, reject) => {
    const worker = new Worker(RUNNER, { workerData: { ticks: TICKS } });
    const timer = setTimeout(() => void worker.terminate(), 30_000);
    worker.once('message', (m) => {
      clearTimeout(timer);
      resolve(m as string[]);
      void worker.terminate();
    });
    worker.once('error', (e) => {
      clearTimeout(timer);
      reject(e);
    });
  });
}

async function inProcess(): Promise<string[]> {
  const sim = await makeSim(undefined, { boxes: 12 }, 'cross-runtime');
  const hashes = runHashes(sim, botRecords(TICKS, { bots: 3, leaveTicks: [-1, 70, -1] }));
  sim.destroy();
  return hashes;
}

describe('state-hash', () => {
  it('digests to 16 lowercase hex characters', () => {
    expect(hashWords(new Uint32Array([1, 2, 3]))).toMatch(/^[0-9a-f]{16}$/);
  });

  it('changes when any word, the word order or the length changes', () => {
    const base = hashWords(new Uint32Array([1, 2, 3, 4]));
    expect(hashWords(new Uint32Array([1, 2, 3, 5]))).not.toBe(base);
    expect(hashWords(new Uint32Array([2, 1, 3, 4]))).not.toBe(base);
    expect(hashWords(new Uint32Array([1, 2, 3, 4, 0]))).not.toBe(base);
    expect(hashWords(new Uint32Array([1, 2, 3, 4]))).toBe(base);
  });

  it('spreads single-bit changes over both 32-bit halves', () => {
    const a = hashWords(new Uint32Array([0x3f800000]));
    const b = hashWords(new Uint32Array([0x3f800001]));
    expect(a.slice(0, 8)).not.toBe(b.slice(0, 8));
    expect(a.slice(8)).not.toBe(b.slice(8));
  });

  it('hashes words fed one by one like words fed as an array', () => {
    const words = new Uint32Array([7, 0xffffffff, 0, 0x80000000]);
    const h = new Hasher64();
    for (const w of words) h.word(w);
    expect(h.hex()).toBe(hashWords(words));
  });

  it('starts over on reset exactly as a new hasher with that seed', () => {
    const h = new Hasher64(5).word(9).string('used');
    expect(h.reset().word(1).f64Bits(0.5).string('taos').hex()).toBe('6f4c87e66b05c1ec');
    expect(h.reset(3).word(7).hex()).toBe(new Hasher64(3).word(7).hex());
  });

  it('matches the test vector published in docs/simulation.md (a changed function would void every golden)', () => {
    expect(new Hasher64().word(1).f64Bits(0.5).string('taos').hex()).toBe('6f4c87e66b05c1ec');
  });

  it('gives identical per-tick hashes in this process and in two child processes', async () => {
    const [here, a, b] = await Promise.all([inProcess(), inChildProcess(), inChildProcess()]);
    expect(here).toHaveLength(TICKS);
    expect(new Set(here).size).toBe(TICKS);
    expect(a).toEqual(here);
    expect(b).toEqual(here);
  });

  it('gives identical per-tick hashes in two worker threads', async () => {
    const [here, a, b] = await Promise.all([inProcess(), inWorker(), inWorker()]);
    expect(a).toEqual(here);
    expect(b).toEqual(here);
  });
});
