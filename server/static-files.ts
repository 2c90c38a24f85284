// Serves the built browser client (a directory of static files) over HTTP GET/HEAD, refusing paths that escape it,
// and answers with a clear text page when the client has not been built yet. `/name` serves `name.html` when there
// is no file `name`; files under chunks/ carry a content hash in their names and are cached for good.
import { createReadStream, type Stats } from 'node:fs';
import { stat } from 'node:fs/promises';
import type { IncomingMessage, ServerResponse } from 'node:http';
import { extname, resolve, sep } from 'node:path';
import { HttpErrorCode, sendError } from './http-errors.ts';

const CONTENT_TYPES: Readonly<Record<string, string>> = {
  '.html': 'text/html; charset=utf-8',
  '.js': 'text/javascript; charset=utf-8',
  '.mjs': 'text/javascript; charset=utf-8',
  '.css': 'text/css; charset=utf-8',
  '.json': 'application/json; charset=utf-8',
  '.map': 'application/json; charset=utf-8',
  '.wasm': 'application/wasm',
  '.wgsl': 'text/plain; charset=utf-8',
  '.txt': 'text/plain; charset=utf-8',
  '.svg': 'image/svg+xml',
  '.png': 'image/png',
  '.ico': 'image/x-icon',
};

/** Where the build puts content-hashed files (split chunks, Jolt's .wasm): their bytes never change under a name. */
const IMMUTABLE_PREFIX = '/chunks/';
/** cache-control of content-hashed files. */
export const IMMUTABLE_CACHE_CONTROL = 'public, max-age=31536000, immutable';

/** The page served at / when the client directory has no index.html. */
export function notBuiltPage(rootDir: string): string {
  return [
    'taos-physics server is running, but the browser client has not been built.',
    '',
    `Expected its files in: ${rootDir}`,
    'Build it with:  npm run build   (then reload this page)',
    '',
    'The server API is up meanwhile: /healthz, /metrics, /api/rooms, and WebSocket on this same port.',
    '',
  ].join('\n');
}

async function fileStats(path: string): Promise<Stats | null> {
  try {
    return await stat(path);
  } catch {
    return null;
  }
}

/**
 * A request handler for static files under `rootDir`; resolves true when it answered the request. With
 * `fallThrough`, a missing file is left to the next handler (resolves false) instead of answered 404.
 */
export function createStaticHandler(rootDir: string, fallThrough = false): (req: IncomingMessage, res: ServerResponse) => Promise<boolean> {
  const root = resolve(rootDir);
  return async (req, res) => {
    if (req.method !== 'GET' && req.method !== 'HEAD') return false;
    let pathname: string;
    try {
      pathname = decodeURIComponent(new URL(req.url ?? '/', 'http://localhost').pathname);
    } catch {
      sendError(res, 400, HttpErrorCode.BadUrl, 'the request path is not a valid URL path (malformed percent-encoding?)');
      return true;
    }
    if (pathname.includes('\0')) {
      sendError(res, 400, HttpErrorCode.BadUrl, 'the request path contains a NUL character');
      return true;
    }
    const relative = pathname.endsWith('/') ? `${pathname}index.html` : pathname;
    const full = resolve(root, `.${relative}`);
    if (full !== root && !full.startsWith(root + sep)) {
      sendError(res, 403, HttpErrorCode.Forbidden, 'the path leaves the client directory');
      return true;
    }
    let info = await fileStats(full);
    let path = full;
    if (info?.isDirectory()) {
      path = resolve(full, 'index.html');
      info = await fileStats(path);
    } else if (!info && extname(full) === '' && full !== root) {
      path = `${full}.html`;
      info = await fileStats(path);
    }
    if (!info || !info.isFile()) {
      if (fallThrough) return false;
      if (pathname === '/' || pathname === '/index.html') {
        res.writeHead(503, { 'content-type': 'text/plain; charset=utf-8', 'cache-control': 'no-store' });
        res.end(req.method === 'HEAD' ? undefined : notBuiltPage(root));
        return true;
      }
      sendError(res, 404, HttpErrorCode.NotFound, `no file ${JSON.stringify(pathname.slice(0, 200))}`);
      return true;
    }
    res.writeHead(200, {
      'content-type': CONTENT_TYPES[extname(path).toLowerCase()] ?? 'application/octet-stream',
      'content-length': info.size,
      'cache-control': pathname.startsWith(IMMUTABLE_PREFIX) ? IMMUTABLE_CACHE_CONTROL : 'no-cache',
      'x-content-type-options': 'nosniff',
    });
    if (req.method === 'HEAD') {
      res.end();
      return true;
    }
    await new Promise<void>((done) => {
      const stream = createReadStream(path);
      stream.on('error', () => {
        res.destroy();
        done();
      });
      stream.on('end', () => done());
      stream.pipe(res);
    });
    return true;
  };
}
