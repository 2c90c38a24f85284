// Structured logging for the server: a pino logger (JSON lines, or pretty lines for a terminal; written synchronously:
// the server logs events, not per-tick data, so nothing is ever lost at exit) with a level, silent in tests, and a
// flush used by shutdown.
import { pino, type Logger } from 'pino';
import { LogFormat, prettyDestination } from './pretty-log.ts';

export type { Logger } from 'pino';

/** Options of createLogger. */
export interface LoggerOptions {
  /** pino level name; 'silent' disables output. Default: TAOS_LOG_LEVEL, else 'silent' under vitest, else 'info'. */
  level?: string;
  /** Where lines go: a file descriptor (default 1, stdout). */
  fd?: number;
  /** JSON lines (default) or human-readable lines (server/pretty-log.ts). */
  format?: LogFormat;
  /** Colour the level in pretty lines (a terminal). Default false. */
  colour?: boolean;
}

/** The default level: quiet under vitest unless TAOS_LOG_LEVEL says otherwise. */
export function defaultLogLevel(): string {
  const env = process.env.TAOS_LOG_LEVEL;
  if (env) return env;
  return process.env.VITEST ? 'silent' : 'info';
}

/** Creates the server's logger. */
export function createLogger(opts: LoggerOptions = {}): Logger {
  const level = opts.level ?? defaultLogLevel();
  if (opts.format === LogFormat.Pretty) return pino({ level, base: { service: 'taos-physics' } }, prettyDestination(opts.fd ?? 1, opts.colour ?? false));
  const destination = pino.destination({ dest: opts.fd ?? 1, sync: true });
  return pino({ level, base: { service: 'taos-physics' } }, destination);
}

/** A logger that drops everything. */
export function silentLogger(): Logger {
  return pino({ level: 'silent' });
}

/** Resolves once the logger's lines have been handed to the OS (never rejects). */
export function flushLogger(logger: Logger): Promise<void> {
  return new Promise((resolve) => {
    try {
      logger.flush(() => resolve());
    } catch {
      resolve();
    }
  });
}
