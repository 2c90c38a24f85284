// A throw-away Debian `redis-server` on a loopback port (no persistence), started on a port picked by binding first
// (redis cannot listen on port 0) and stopped by its PID. No test framework here: the bench uses it too.
import { spawn, type ChildProcess } from 'node:child_process';
import { existsSync } from 'node:fs';
import { createServer, connect } from 'node:net';

/** Where redis-server is looked for (override with REDIS_SERVER_PATH). */
export const REDIS_SERVER_PATH = process.env.REDIS_SERVER_PATH ?? '/usr/bin/redis-server';

/** Why redis-server cannot run here, or null when it can. */
export function redisMissingReason(): string | null {
  if (!existsSync(REDIS_SERVER_PATH)) return `redis-server not found at ${REDIS_SERVER_PATH} (install Debian's redis-server: apt-get install -y redis-server, or set REDIS_SERVER_PATH)`;
  return null;
}

/** A free loopback TCP port (redis cannot listen on port 0): bound, read, released. */
export async function freePort(): Promise<number> {
  const server = createServer();
  await new Promise<void>((resolve, reject) => {
    server.once('error', reject);
    server.listen(0, '127.0.0.1', () => resolve());
  });
  const address = server.address();
  const port = typeof address === 'object' && address !== null ? address.port : 0;
  await new Promise<void>((resolve) => server.close(() => resolve()));
  return port;
}

/** Resolves when `PING` on host:port answers `+PONG`, or rejects after timeoutMs. */
async function waitForPong(port: number, timeoutMs: number, exited: () => string | null): Promise<void> {
  const deadline = Date.now() + timeoutMs;
  for (;;) {
    const ok = await new Promise<boolean>((resolve) => {
      const socket = connect(port, '127.0.0.1');
      let text = '';
      socket.setTimeout(500, () => socket.destroy());
      socket.on('connect', () => socket.write('PING\r\n'));
      socket.on('data', (d) => {
        text += d.toString('latin1');
        if (text.includes('\r\n')) {
          socket.destroy();
          resolve(text.startsWith('+PONG'));
        }
      });
      socket.on('error', () => resolve(false));
      socket.on('close', () => resolve(false));
    });
    if (ok) return;
    const why = exited();
    if (why !== null) throw new Error(`redis-server exited before answering: ${why}`);
    if (Date.now() > deadline) throw new Error(`redis-server on port ${port} did not answer PING within ${timeoutMs} ms`);
    await new Promise((r) => setTimeout(r, 50));
  }
}

/** A running redis-server. */
export interface RedisServer {
  readonly port: number;
  readonly url: string;
  readonly pid: number;
  /** Stops it (SIGTERM by PID, SIGKILL after 3 s) and waits for the exit. */
  stop(): Promise<void>;
}

/**
 * Starts redis-server without persistence on `opts.port` (default: a free loopback port) and waits until it answers.
 * `debugCommand` allows DEBUG (e.g. DEBUG SLEEP to play a stalled Redis).
 */
export async function startRedisServer(opts: { port?: number; debugCommand?: boolean } = {}): Promise<RedisServer> {
  for (let attempt = 0; ; attempt++) {
    const port = opts.port ?? (await freePort());
    const extra = opts.debugCommand ? ['--enable-debug-command', 'yes'] : [];
    const child: ChildProcess = spawn(REDIS_SERVER_PATH, ['--port', String(port), '--bind', '127.0.0.1', '--save', '', '--appendonly', 'no', '--protected-mode', 'yes', ...extra], {
      stdio: ['ignore', 'pipe', 'pipe'],
    });
    let output = '';
    child.stdout?.on('data', (d: Buffer) => (output = (output + d.toString('utf8')).slice(-2000)));
    child.stderr?.on('data', (d: Buffer) => (output = (output + d.toString('utf8')).slice(-2000)));
    let exit: string | null = null;
    const exited = new Promise<void>((resolve) =>
      child.once('exit', (code, signal) => {
        exit = `code ${code} signal ${signal}: ${output.trim().split('\n').slice(-3).join(' | ')}`;
        resolve();
      }),
    );
    try {
      await waitForPong(port, 10_000, () => exit);
    } catch (error) {
      if (child.exitCode === null) child.kill('SIGKILL');
      await exited;
      // Another process may have taken the port between our probe and redis binding it: try another once or twice.
      if (attempt < 2 && opts.port === undefined && /Address already in use/.test(output)) continue;
      throw error;
    }
    const pid = child.pid ?? 0;
    return {
      port,
      url: `redis://127.0.0.1:${port}`,
      pid,
      async stop() {
        if (child.exitCode !== null || child.signalCode !== null) return;
        process.kill(pid, 'SIGTERM');
        const timer = setTimeout(() => child.exitCode === null && child.signalCode === null && process.kill(pid, 'SIGKILL'), 3000);
        await exited;
        clearTimeout(timer);
      },
    };
  }
}
