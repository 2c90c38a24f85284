// Tests for server/last-resort.ts: an uncaught exception or unhandled rejection is counted by kind and logged once,
// a failing logger does not escape the handler, and uninstalling removes exactly the handlers it added.
import { EventEmitter } from 'node:events';
import { pino } from 'pino';
import { describe, expect, it } from 'vitest';
import { installLastResort } from '../../server/last-resort.ts';
import { silentLogger } from '../../server/logger.ts';
import { createMetrics } from '../../server/metrics.ts';

describe('installLastResort', () => {
  it('counts and logs each uncaught exception and unhandled rejection, and goes on', async () => {
    const source = new EventEmitter();
    const metrics = createMetrics({ processMetrics: false });
    const lines: Array<{ level: number; msg: string; kind: string; err?: { message: string } }> = [];
    const logger = pino({ level: 'info' }, { write: (line: string) => void lines.push(JSON.parse(line) as (typeof lines)[number]) });
    installLastResort({ logger, metrics, source });
    source.emit('uncaughtException', new Error('first'));
    source.emit('uncaughtException', new Error('second'));
    source.emit('unhandledRejection', new Error('later'));
    const text = await metrics.registry.getSingleMetricAsString('taos_uncaught_errors_total');
    expect(text).toContain('taos_uncaught_errors_total{kind="exception"} 2');
    expect(text).toContain('taos_uncaught_errors_total{kind="rejection"} 1');
    expect(lines.map((l) => [l.level, l.kind, l.err?.message])).toEqual([
      [50, 'exception', 'first'],
      [50, 'exception', 'second'],
      [50, 'rejection', 'later'],
    ]);
  });

  it('still counts when the logger itself throws', async () => {
    const source = new EventEmitter();
    const metrics = createMetrics({ processMetrics: false });
    const logger = silentLogger();
    logger.error = () => {
      throw new Error('logger down');
    };
    installLastResort({ logger, metrics, source });
    expect(() => source.emit('uncaughtException', 'a thrown string')).not.toThrow();
    expect(await metrics.registry.getSingleMetricAsString('taos_uncaught_errors_total')).toContain('{kind="exception"} 1');
  });

  it('removes its handlers when uninstalled', () => {
    const source = new EventEmitter();
    const uninstall = installLastResort({ logger: silentLogger(), metrics: createMetrics({ processMetrics: false }), source });
    expect([source.listenerCount('uncaughtException'), source.listenerCount('unhandledRejection')]).toEqual([1, 1]);
    uninstall();
    expect([source.listenerCount('uncaughtException'), source.listenerCount('unhandledRejection')]).toEqual([0, 0]);
  });
});
