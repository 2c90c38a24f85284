// Node side of the cross-runtime determinism check: builds the production client (scripts/build-client.ts) into a
// temporary directory, bundles page.ts beside it, serves both with a job naming the built physics chunk on
// 127.0.0.1, and hands back what a browser POSTs to /result.
import { build } from 'esbuild';
import { mkdtemp, readFile, rm, writeFile } from 'node:fs/promises';
import { createServer, type IncomingMessage } from 'node:http';
import type { AddressInfo } from 'node:net';
import { tmpdir } from 'node:os';
import { join } from 'node:path';
import { fileURLToPath } from 'node:url';
import { buildClient } from '../../../scripts/build-client.ts';
import { GOLDEN_HASH_EVERY_TICKS, GOLDEN_JOIN_SPACING_TICKS, GOLDEN_SEED } from '../../../shared/sim/golden.ts';
import { createStaticHandler } from '../../../server/static-files.ts';
import type { ResumeJob, SimCheckJob, SimCheckResult } from './protocol.ts';

const PAGE_ENTRY = fileURLToPath(new URL('./page.ts', import.meta.url));
/** The largest result body accepted (hashes of every scenario: a few tens of KiB). */
const MAX_RESULT_BYTES = 4 << 20;

/** A served check page; `nextResult()` resolves with the next POSTed result. */
export interface SimCheckHost {
  url: string;
  nextResult(timeoutMs: number): Promise<SimCheckResult>;
  close(): Promise<void>;
}

async function readBody(req: IncomingMessage): Promise<string> {
  const chunks: Buffer[] = [];
  let size = 0;
  for await (const chunk of req) {
    size += (chunk as Buffer).byteLength;
    if (size > MAX_RESULT_BYTES) throw new Error('result too large');
    chunks.push(chunk as Buffer);
  }
  return Buffer.concat(chunks).toString('utf8');
}

/** Bundles the page into a temporary directory and serves it with `resumes` as its job. */
export async function startSimCheckHost(resumes: ResumeJob[]): Promise<SimCheckHost> {
  const dir = await mkdtemp(join(tmpdir(), 'taos-sim-check-'));
  try {
    const built = await buildClient({ outDir: dir });
    const physicsChunk = built.split.physicsChunk;
    if (!physicsChunk) throw new Error('the client build has no physics chunk');
    await build({
      entryPoints: [PAGE_ENTRY],
      outfile: join(dir, 'sim-check.js'),
      bundle: true,
      format: 'esm',
      platform: 'browser',
      target: ['es2022'],
      logLevel: 'silent',
    });
    // The page must use the shipped chunk's Simulation, not a copy of its own.
    if (/JoltInterface/.test(await readFile(join(dir, 'sim-check.js'), 'utf8'))) throw new Error('sim-check.js bundles Jolt itself; it must load the physics chunk');
    await writeFile(join(dir, 'sim-check.html'), '<!doctype html><meta charset="utf-8"><title>sim-check</title><link rel="icon" href="data:,"><script type="module" src="sim-check.js"></script>\n');
    const job: SimCheckJob = { physicsChunk, golden: { seed: GOLDEN_SEED, joinSpacingTicks: GOLDEN_JOIN_SPACING_TICKS, hashEveryTicks: GOLDEN_HASH_EVERY_TICKS }, resumes };
    await writeFile(join(dir, 'job.json'), JSON.stringify(job));
  } catch (err) {
    await rm(dir, { recursive: true, force: true });
    throw err;
  }
  const statics = createStaticHandler(dir);
  const waiting: Array<(r: SimCheckResult) => void> = [];
  const arrived: SimCheckResult[] = [];
  const server = createServer((req, res) => {
    if (req.method === 'POST' && req.url === '/result') {
      readBody(req)
        .then((text) => {
          const result = JSON.parse(text) as SimCheckResult;
          res.writeHead(204).end();
          const w = waiting.shift();
          if (w) w(result);
          else arrived.push(result);
        })
        .catch((err: unknown) => res.writeHead(400).end(String(err)));
      return;
    }
    statics(req, res)
      .then((answered) => {
        if (!answered) res.writeHead(405).end();
      })
      .catch(() => res.writeHead(500).end());
  });
  await new Promise<void>((resolve) => server.listen(0, '127.0.0.1', resolve));
  const { port } = server.address() as AddressInfo;
  return {
    url: `http://127.0.0.1:${port}/sim-check.html`,
    nextResult(timeoutMs) {
      const ready = arrived.shift();
      if (ready) return Promise.resolve(ready);
      return new Promise((resolve, reject) => {
        const timer = setTimeout(() => {
          waiting.splice(waiting.indexOf(done), 1);
          reject(new Error(`no result from the browser within ${timeoutMs} ms`));
        }, timeoutMs);
        const done = (r: SimCheckResult): void => {
          clearTimeout(timer);
          resolve(r);
        };
        waiting.push(done);
      });
    },
    async close() {
      server.closeAllConnections();
      await new Promise<void>((resolve) => server.close(() => resolve()));
      await rm(dir, { recursive: true, force: true });
    },
  };
}
