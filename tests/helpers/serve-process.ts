// `taos-physics serve` in a child process for multi-process tests: started on a free port (port 0), its URL read from
// the line it prints, stopped by its PID (SIGTERM for a clean exit, SIGKILL to play a crash).
import { spawn, type ChildProcess } from 'node:child_process';
import { dirname, join, resolve } from 'node:path';
import { fileURLToPath } from 'node:url';

const BIN = join(resolve(dirname(fileURLToPath(import.meta.url)), '..', '..'), 'bin', 'taos-physics.js');

/** A running serve process. */
export interface ServeProcess {
  /** http://127.0.0.1:PORT/ */
  readonly url: string;
  /** ws://127.0.0.1:PORT/ */
  readonly wsUrl: string;
  readonly pid: number;
  /** Its stderr so far (JSON log lines). */
  log(): string;
  /** Resolves with the exit code once the process exits by itself; rejects after timeoutMs. */
  exited(timeoutMs: number): Promise<number | null>;
  /** Sends `signal` by PID and resolves when it exited (SIGKILL after 10 s if it has not). */
  stop(signal?: 'SIGTERM' | 'SIGKILL'): Promise<void>;
}

/** Starts `serve --port 0 --host 127.0.0.1 …args` and resolves once it prints where it listens. */
export async function startServeProcess(args: readonly string[], env: NodeJS.ProcessEnv = {}): Promise<ServeProcess> {
  const child: ChildProcess = spawn(process.execPath, [BIN, 'serve', '--port', '0', '--host', '127.0.0.1', ...args], {
    stdio: ['ignore', 'pipe', 'pipe'],
    env: { ...process.env, ...env },
  });
  let stdout = '';
  let stderr = '';
  child.stderr?.on('data', (d: Buffer) => (stderr = (stderr + d.toString('utf8')).slice(-200_000)));
  const exited = new Promise<number | null>((done) => child.once('exit', (code) => done(code)));
  const url = await new Promise<string>((resolveUrl, reject) => {
    const timer = setTimeout(() => reject(new Error(`serve did not start within 30 s: ${stderr.slice(-1000)}`)), 30_000);
    child.stdout?.on('data', (d: Buffer) => {
      stdout += d.toString('utf8');
      const m = / at (http:\/\/[^ ]+\/) /.exec(stdout);
      if (m) {
        clearTimeout(timer);
        resolveUrl(m[1]);
      }
    });
    child.once('exit', (code) => {
      clearTimeout(timer);
      reject(new Error(`serve exited with ${code} before listening: ${stdout}${stderr.slice(-2000)}`));
    });
  });
  const pid = child.pid ?? 0;
  return {
    url,
    wsUrl: url.replace(/^http/, 'ws'),
    pid,
    log: () => stderr,
    exited: (timeoutMs) =>
      new Promise<number | null>((resolveExit, reject) => {
        const timer = setTimeout(() => reject(new Error(`serve did not exit within ${timeoutMs} ms`)), timeoutMs);
        void exited.then((code) => {
          clearTimeout(timer);
          resolveExit(code);
        });
      }),
    async stop(signal = 'SIGTERM') {
      if (child.exitCode !== null || child.signalCode !== null) return;
      process.kill(pid, signal);
      const timer = setTimeout(() => child.exitCode === null && child.signalCode === null && process.kill(pid, 'SIGKILL'), 10_000);
      await exited;
      clearTimeout(timer);
    },
  };
}
