// Tests for server/static-files.ts: serving the built client, content types, extensionless pages, caching of
// content-hashed chunks, traversal refusal, not-built page.
import { mkdtempSync, mkdirSync, rmSync, writeFileSync } from 'node:fs';
import type { IncomingMessage, ServerResponse } from 'node:http';
import { tmpdir } from 'node:os';
import { join } from 'node:path';
import { PassThrough } from 'node:stream';
import { afterAll, describe, expect, it } from 'vitest';
import { createStaticHandler } from '../../server/static-files.ts';

interface Captured {
  status: number;
  headers: Record<string, string | number>;
  body: string;
}

// A minimal ServerResponse stand-in: records writeHead and collects the body (files are piped into it).
async function request(handler: ReturnType<typeof createStaticHandler>, method: string, url: string): Promise<Captured | null> {
  const out: Captured = { status: 0, headers: {}, body: '' };
  const sink = new PassThrough();
  const chunks: Buffer[] = [];
  sink.on('data', (c: Buffer) => chunks.push(c));
  const finished = new Promise<void>((resolve) => sink.on('end', () => resolve()));
  const res = Object.assign(sink, {
    writeHead(status: number, headers: Record<string, string | number>) {
      out.status = status;
      out.headers = headers;
      return res;
    },
  }) as unknown as ServerResponse;
  const handled = await handler({ method, url } as IncomingMessage, res);
  if (!handled) return null;
  if (!sink.writableEnded) sink.end();
  await finished;
  out.body = Buffer.concat(chunks).toString('utf8');
  return out;
}

const dir = mkdtempSync(join(tmpdir(), 'taos-static-'));
mkdirSync(join(dir, 'assets'));
writeFileSync(join(dir, 'index.html'), '<!doctype html><title>t</title>');
writeFileSync(join(dir, 'assets', 'app.js'), 'console.log(1)');
writeFileSync(join(dir, 'assets', 'jolt.wasm'), Buffer.from([0, 97, 115, 109]));
writeFileSync(join(dir, 'replay.html'), '<!doctype html><title>replay</title>');
mkdirSync(join(dir, 'chunks'));
writeFileSync(join(dir, 'chunks', 'jolt-physics-0123456789abcdef.wasm'), Buffer.from([0, 97, 115, 109, 1, 0, 0, 0]));
writeFileSync(join(dir, '..', 'taos-secret.txt'), 'secret');
afterAll(() => {
  rmSync(dir, { recursive: true, force: true });
  rmSync(join(dir, '..', 'taos-secret.txt'), { force: true });
});

describe('static-files', () => {
  it('serves index.html at / and files with their content types', async () => {
    const handler = createStaticHandler(dir);
    const index = await request(handler, 'GET', '/');
    expect(index?.status).toBe(200);
    expect(index?.headers['content-type']).toMatch(/text\/html/);
    expect(index?.body).toContain('<title>t</title>');
    const js = await request(handler, 'GET', '/assets/app.js?v=3');
    expect(js?.headers['content-type']).toMatch(/javascript/);
    expect(js?.body).toBe('console.log(1)');
    const wasm = await request(handler, 'GET', '/assets/jolt.wasm');
    expect(wasm?.headers['content-type']).toBe('application/wasm');
  });

  it('serves name.html at /name, and content-hashed chunks as cacheable for good while pages revalidate', async () => {
    const handler = createStaticHandler(dir);
    const page = await request(handler, 'GET', '/replay');
    expect(page?.status).toBe(200);
    expect(page?.body).toContain('<title>replay</title>');
    expect(page?.headers['cache-control']).toBe('no-cache');
    const wasm = await request(handler, 'GET', '/chunks/jolt-physics-0123456789abcdef.wasm');
    expect(wasm?.status).toBe(200);
    expect(wasm?.headers['content-type']).toBe('application/wasm');
    expect(wasm?.headers['cache-control']).toBe('public, max-age=31536000, immutable');
    expect((await request(handler, 'GET', '/assets/jolt.wasm'))?.headers['cache-control']).toBe('no-cache');
    expect((await request(handler, 'GET', '/nope'))?.status).toBe(404);
  });

  it('answers HEAD without a body', async () => {
    const res = await request(createStaticHandler(dir), 'HEAD', '/assets/app.js');
    expect(res?.status).toBe(200);
    expect(res?.headers['content-length']).toBe(14);
    expect(res?.body).toBe('');
  });

  it('refuses paths that climb out of the directory', async () => {
    const handler = createStaticHandler(dir);
    const res = await request(handler, 'GET', `/..%2Ftaos-secret.txt`);
    expect(res?.status).toBe(403);
    expect(res?.body).not.toContain('secret\n');
    expect(JSON.parse(res!.body)).toEqual({ error: 'forbidden', message: 'the path leaves the client directory' });
    expect((await request(handler, 'GET', '/a%00b'))?.status).toBe(400);
    const malformed = await request(handler, 'GET', '/%E0%A4%A');
    expect(malformed?.status).toBe(400);
    expect(JSON.parse(malformed!.body)).toMatchObject({ error: 'bad-url' });
  });

  it('returns 404 for missing files and leaves other methods to the next handler', async () => {
    const handler = createStaticHandler(dir);
    const missing = await request(handler, 'GET', '/nope.js');
    expect(missing?.status).toBe(404);
    expect(JSON.parse(missing!.body)).toEqual({ error: 'not-found', message: 'no file "/nope.js"' });
    expect(await request(handler, 'POST', '/')).toBeNull();
  });

  it('explains how to build the client when it has not been built', async () => {
    const res = await request(createStaticHandler(join(dir, 'missing')), 'GET', '/');
    expect(res?.status).toBe(503);
    expect(res?.body).toMatch(/has not been built/);
    expect(res?.body).toMatch(/npm run build/);
  });
});
