// Clean shutdown on SIGINT/SIGTERM: the first signal closes the server (clients get a bye with the reason, rooms stop,
// recordings and logs are flushed) and exits 0; a second signal, or a close that hangs, exits 1 at once.
import type { Logger } from './logger.ts';
import { flushLogger } from './logger.ts';

/** Something that can be shut down with a reason. */
export interface Closable {
  close(reason: string): Promise<void>;
}

/** The bits of `process` shutdown uses (injectable for tests). */
export interface SignalSource {
  on(signal: string, fn: () => void): unknown;
  off(signal: string, fn: () => void): unknown;
}

/** Options of installShutdown. */
export interface ShutdownOptions {
  logger: Logger;
  signals?: readonly string[];
  /** Exit after a hung close; default 10 s. */
  forceAfterMs?: number;
  /** How to end the process; default process.exit. */
  exit?: (code: number) => void;
  source?: SignalSource;
}

/** Installs the handlers; returns a function that removes them (and a promise that settles when shutdown ran). */
export function installShutdown(target: Closable, opts: ShutdownOptions): { uninstall(): void; done: Promise<number> } {
  const signals = opts.signals ?? ['SIGINT', 'SIGTERM'];
  const source: SignalSource = opts.source ?? process;
  const exit = opts.exit ?? ((code: number) => process.exit(code));
  let shuttingDown = false;
  let settle: (code: number) => void = () => {};
  const done = new Promise<number>((resolve) => (settle = resolve));
  const handlers = new Map<string, () => void>();

  const finish = (code: number): void => {
    settle(code);
    exit(code);
  };

  for (const signal of signals) {
    const fn = (): void => {
      if (shuttingDown) {
        opts.logger.warn({ signal }, 'second signal: exiting now');
        void flushLogger(opts.logger).finally(() => finish(1));
        return;
      }
      shuttingDown = true;
      opts.logger.info({ signal }, 'shutting down');
      const force = setTimeout(() => {
        opts.logger.error({ signal, afterMs: opts.forceAfterMs ?? 10_000 }, 'shutdown hung: exiting');
        void flushLogger(opts.logger).finally(() => finish(1));
      }, opts.forceAfterMs ?? 10_000);
      force.unref();
      target
        .close(`server shutting down (${signal})`)
        .then(
          () => 0,
          (error: unknown) => {
            opts.logger.error({ err: error }, 'error while shutting down');
            return 1;
          },
        )
        .then(async (code) => {
          clearTimeout(force);
          opts.logger.info({ code }, 'shutdown complete');
          await flushLogger(opts.logger);
          finish(code);
        });
    };
    handlers.set(signal, fn);
    source.on(signal, fn);
  }

  return {
    uninstall: () => {
      for (const [signal, fn] of handlers) source.off(signal, fn);
      handlers.clear();
    },
    done,
  };
}
