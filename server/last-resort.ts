// The serving process's last line of defence: an exception or promise rejection that nothing else caught is logged
// and counted (taos_uncaught_errors_total) instead of ending the process, so one failure never stops every room.
// Everything that can be caught closer to its cause is (a client's message, a room's tick); this is for the rest.
import type { Logger } from './logger.ts';
import type { ServerMetrics } from './metrics.ts';

/** The part of `process` the handler uses (injectable for tests). */
export interface UncaughtSource {
  on(event: 'uncaughtException' | 'unhandledRejection', fn: (error: unknown) => void): unknown;
  off(event: 'uncaughtException' | 'unhandledRejection', fn: (error: unknown) => void): unknown;
}

/** Installs the handlers on `source` (default: the process); returns a function that removes them. */
export function installLastResort(opts: { logger: Logger; metrics: ServerMetrics; source?: UncaughtSource }): () => void {
  const source: UncaughtSource = opts.source ?? process;
  const report = (kind: 'exception' | 'rejection', error: unknown): void => {
    // Neither counting nor logging may throw from here: Node would end the process after all.
    try {
      opts.metrics.uncaughtErrors.inc({ kind });
    } catch {
      // a broken registry must not take the process down either
    }
    try {
      opts.logger.error({ err: error, kind }, kind === 'exception' ? 'uncaught exception; the server goes on' : 'unhandled promise rejection; the server goes on');
    } catch {
      // the logger failed: the count above still says it happened
    }
  };
  const onException = (error: unknown): void => report('exception', error);
  const onRejection = (reason: unknown): void => report('rejection', reason);
  source.on('uncaughtException', onException);
  source.on('unhandledRejection', onRejection);
  return () => {
    source.off('uncaughtException', onException);
    source.off('unhandledRejection', onRejection);
  };
}
