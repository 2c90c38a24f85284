// Tests of server/replay-log.ts: `serve --replay FILE` refuses a file that is not a readable input log before the
// server starts, serves the log's current bytes with its name at /replay.taoslog, and leaves other requests alone.
import { mkdtemp, rm, writeFile } from 'node:fs/promises';
import type { IncomingMessage, ServerResponse } from 'node:http';
import { tmpdir } from 'node:os';
import { join } from 'node:path';
import { afterAll, beforeAll, describe, expect, it } from 'vitest';
import { LogEncoder } from '../../server/log/log-encoder.ts';
import { checkReplayLog, REPLAY_LOG_PATH, withReplayLog } from '../../server/replay-log.ts';
import { sampleHeader, sampleTick } from '../helpers/input-log.ts';

interface Answer {
  status: number;
  headers: Record<string, string | number>;
  body: Buffer;
}

/** Runs a handler on a fake request; null when it passed the request on. */
async function ask(handler: ReturnType<typeof withReplayLog>, method: string, url: string): Promise<Answer | null> {
  const answer: Answer = { status: 0, headers: {}, body: Buffer.alloc(0) };
  const res = {
    writeHead(status: number, headers: Record<string, string | number>) {
      answer.status = status;
      answer.headers = headers;
      return res;
    },
    setHeader() {
      return res;
    },
    end(body?: Buffer | string) {
      if (body !== undefined) answer.body = Buffer.from(body);
      return res;
    },
  } as unknown as ServerResponse;
  const handled = await handler({ method, url, headers: {} } as IncomingMessage, res);
  return handled ? answer : null;
}

describe('replay-log', () => {
  let dir: string;
  let logPath: string;
  let bytes: Uint8Array;
  const passed: string[] = [];
  const next = async (req: IncomingMessage): Promise<boolean> => {
    passed.push(`${req.method} ${req.url}`);
    return false;
  };

  beforeAll(async () => {
    dir = await mkdtemp(join(tmpdir(), 'taos-replay-log-'));
    const enc = new LogEncoder(sampleHeader());
    bytes = Buffer.concat([enc.start(), enc.tick(sampleTick(0)), enc.tick(sampleTick(1))]);
    logPath = join(dir, 'séance.taoslog');
    await writeFile(logPath, bytes);
    await writeFile(join(dir, 'notes.txt'), 'hello');
  });

  afterAll(async () => {
    await rm(dir, { recursive: true, force: true });
  });

  it('accepts an input log and refuses a missing file or one that is not a log, naming the flag and the file', async () => {
    await expect(checkReplayLog(logPath)).resolves.toBeUndefined();
    await expect(checkReplayLog(join(dir, 'missing.taoslog'))).rejects.toThrow(/^--replay .*missing\.taoslog: cannot read it \(ENOENT\)$/);
    await expect(checkReplayLog(join(dir, 'notes.txt'))).rejects.toThrow(/^--replay .*notes\.txt: .*is not a taos-physics input log/);
  });

  it('serves the log at /replay.taoslog with its name, and passes every other request on', async () => {
    const handler = withReplayLog(logPath, next);
    const got = await ask(handler, 'GET', `${REPLAY_LOG_PATH}?t=1`);
    expect(got?.status).toBe(200);
    expect(Buffer.compare(got!.body, Buffer.from(bytes))).toBe(0);
    expect(got?.headers).toMatchObject({ 'content-type': 'application/octet-stream', 'content-length': bytes.byteLength, 'cache-control': 'no-store', 'x-taos-log-name': 's?ance.taoslog' });
    const head = await ask(handler, 'HEAD', REPLAY_LOG_PATH);
    expect(head?.status).toBe(200);
    expect(head?.body.byteLength).toBe(0);
    expect(await ask(handler, 'GET', '/replay')).toBeNull();
    expect(await ask(handler, 'POST', REPLAY_LOG_PATH)).toBeNull();
    expect(passed).toEqual(['GET /replay', `POST ${REPLAY_LOG_PATH}`]);
  });

  it('answers 404 once the log can no longer be read', async () => {
    const gone = join(dir, 'gone.taoslog');
    await writeFile(gone, bytes);
    const handler = withReplayLog(gone, next);
    await rm(gone);
    const got = await ask(handler, 'GET', REPLAY_LOG_PATH);
    expect(got?.status).toBe(404);
    expect(JSON.parse(got!.body.toString('utf8'))).toMatchObject({ error: 'not-found' });
  });
});
