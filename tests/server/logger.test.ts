// Tests for server/logger.ts: JSON lines at the chosen level to the chosen descriptor, flushed on demand.
import { closeSync, mkdtempSync, openSync, readFileSync, rmSync } from 'node:fs';
import { tmpdir } from 'node:os';
import { join } from 'node:path';
import { describe, expect, it } from 'vitest';
import { createLogger, defaultLogLevel, flushLogger, silentLogger } from '../../server/logger.ts';

describe('logger', () => {
  it('writes JSON lines at or above its level and flushes them', async () => {
    const dir = mkdtempSync(join(tmpdir(), 'taos-log-'));
    const fd = openSync(join(dir, 'out.log'), 'w');
    try {
      const log = createLogger({ level: 'info', fd });
      log.debug('hidden');
      log.info({ room: 'default' }, 'room opened');
      log.warn({ skippedTicks: 3 }, 'slowing down');
      await flushLogger(log);
      const lines = readFileSync(join(dir, 'out.log'), 'utf8').trim().split('\n').map((l) => JSON.parse(l) as Record<string, unknown>);
      expect(lines.map((l) => l.msg)).toEqual(['room opened', 'slowing down']);
      expect(lines[0]).toMatchObject({ level: 30, service: 'taos-physics', room: 'default' });
    } finally {
      closeSync(fd);
      rmSync(dir, { recursive: true, force: true });
    }
  });

  it('writes human-readable lines in the pretty format', async () => {
    const dir = mkdtempSync(join(tmpdir(), 'taos-log-'));
    const fd = openSync(join(dir, 'out.log'), 'w');
    try {
      const log = createLogger({ level: 'info', fd, format: 'pretty' });
      log.info({ room: 'default' }, 'room opened');
      await flushLogger(log);
      expect(readFileSync(join(dir, 'out.log'), 'utf8')).toMatch(/^\d\d:\d\d:\d\d\.\d{3} INFO  room opened  room=default\n$/);
    } finally {
      closeSync(fd);
      rmSync(dir, { recursive: true, force: true });
    }
  });

  it('is quiet under vitest unless TAOS_LOG_LEVEL says otherwise, and a silent logger flushes at once', async () => {
    const saved = process.env.TAOS_LOG_LEVEL;
    delete process.env.TAOS_LOG_LEVEL;
    expect(defaultLogLevel()).toBe('silent');
    process.env.TAOS_LOG_LEVEL = 'debug';
    expect(defaultLogLevel()).toBe('debug');
    if (saved === undefined) delete process.env.TAOS_LOG_LEVEL;
    else process.env.TAOS_LOG_LEVEL = saved;
    await expect(flushLogger(silentLogger())).resolves.toBeUndefined();
  });
});
