// The `serve` command's body: starts the server with the command-line options, prints where it listens, logs to
// stderr (pretty lines on a terminal, JSON lines otherwise), keeps going after an uncaught error (last resort: logged and counted), and on SIGINT/SIGTERM
// shuts down cleanly (byes, recordings ended, logs flushed) and returns.
import type { CliIo } from './command.ts';
import { installLastResort } from '../server/last-resort.ts';
import { createLogger } from '../server/logger.ts';
import { LogFormat } from '../server/pretty-log.ts';
import { installShutdown, type SignalSource } from '../server/shutdown.ts';
import { startServer, type StartServerOptions } from '../server/start-server.ts';

/** Options of runServe: the server's plus logging and signal hooks. */
export interface ServeOptions extends Omit<StartServerOptions, 'logger'> {
  /** pino level for the log on stderr. Default info. */
  logLevel?: string;
  /** Log line format on stderr; default pretty when stderr is a terminal, else JSON. */
  logFormat?: LogFormat;
  /** Where signals come from (default the process). */
  signals?: SignalSource;
}

/** Runs until a signal; resolves to the exit code (0 after a clean shutdown, 1 when it failed or hung). */
export async function runServe(opts: ServeOptions, io: CliIo): Promise<number> {
  const format = opts.logFormat ?? (io.stderrIsTTY ? LogFormat.Pretty : LogFormat.Json);
  const logger = createLogger({ level: opts.logLevel ?? process.env.TAOS_LOG_LEVEL ?? 'info', fd: 2, format, colour: io.stderrIsTTY });
  let server;
  try {
    server = await startServer({ ...opts, logger });
  } catch (error) {
    io.stderr(`taos-physics serve: ${error instanceof Error ? error.message : String(error)}\n`);
    logger.flush();
    return 1;
  }
  const room = server.game.rooms.get('default');
  const what = room ? `${room.scenarioName}` : 'no default room';
  const removeLastResort = installLastResort({ logger, metrics: server.game.metrics });
  if (server.resumed) {
    for (const r of server.resumed.rooms) {
      if (server.game.rooms.get(r.id)) io.stdout(`resumed room ${r.id} at tick ${r.tick} (hash ${r.hash}, ${r.players.length} player(s) held) from ${r.path}\n`);
    }
    for (const r of server.resumed.refused) io.stderr(`not resumed: ${r.path}: ${r.reason}\n`);
  }
  io.stdout(`taos-physics serving ${what} at ${server.url} (WebSocket ${server.wsUrl}); Ctrl+C stops\n`);
  if (opts.replayFile) io.stdout(`replay viewer for ${opts.replayFile}: ${new URL('/replay', server.url).href}\n`);
  return new Promise<number>((resolve) => {
    let done = false;
    const exit = (code: number): void => {
      if (done) return;
      done = true;
      uninstall();
      removeLastResort();
      resolve(code);
      // Nothing should hold the event loop after a clean shutdown; if something does, do not hang forever.
      setTimeout(() => process.exit(code), 3000).unref();
    };
    const { uninstall } = installShutdown(server, { logger, source: opts.signals, exit });
    // A single-session server under Agones closes itself once its session is over.
    void server.whenClosed().then(() => exit(0));
  });
}
