// Serves one input log to the replay viewer (`serve --replay FILE`): GET/HEAD /replay.taoslog answers the file's
// bytes (read again on each request, so a log still being written shows its newest ticks); /replay opens it.
// The file is checked to be a readable log when the server starts, so a wrong path fails then, not in the page.
import type { IncomingMessage, ServerResponse } from 'node:http';
import { readFile } from 'node:fs/promises';
import { basename } from 'node:path';
import { readLogBytes } from './log/log-bytes.ts';
import { HttpErrorCode, sendError } from './http-errors.ts';

/** Where the replay viewer fetches the served log. */
export const REPLAY_LOG_PATH = '/replay.taoslog';

/** A request handler: resolves true when it answered. */
export type RequestHandler = (req: IncomingMessage, res: ServerResponse) => Promise<boolean>;

/** Reads `file` and checks that it is an input log with a usable header; throws a clear Error otherwise. */
export async function checkReplayLog(file: string): Promise<void> {
  let bytes: Buffer;
  try {
    bytes = await readFile(file);
  } catch (err) {
    throw new Error(`--replay ${file}: cannot read it (${(err as NodeJS.ErrnoException).code ?? (err as Error).message})`, { cause: err });
  }
  try {
    readLogBytes(bytes, file);
  } catch (err) {
    throw new Error(`--replay ${file}: ${(err as Error).message}`, { cause: err });
  }
}

/** Answers REPLAY_LOG_PATH with `file`'s bytes and hands every other request to `next`. */
export function withReplayLog(file: string, next: RequestHandler): RequestHandler {
  const name = basename(file);
  return async (req, res) => {
    const path = (req.url ?? '/').split('?')[0];
    if (path !== REPLAY_LOG_PATH || (req.method !== 'GET' && req.method !== 'HEAD')) return next(req, res);
    let bytes: Buffer;
    try {
      bytes = await readFile(file);
    } catch {
      sendError(res, 404, HttpErrorCode.NotFound, `the replayed log ${JSON.stringify(name)} can no longer be read`);
      return true;
    }
    res.writeHead(200, {
      'content-type': 'application/octet-stream',
      'content-length': bytes.byteLength,
      'cache-control': 'no-store',
      'x-content-type-options': 'nosniff',
      // The viewer shows this name; header values must be ASCII.
      'x-taos-log-name': name.replace(/[^\x20-\x7e]/g, '?'),
    });
    res.end(req.method === 'HEAD' ? undefined : bytes);
    return true;
  };
}
