// Test helper: builds the package, packs it with npm, and installs the tarball into a fresh project outside the
// repository (npm's cache first: the network only for what the cache lacks). Node 24 runs what was installed.
import { execFile, spawn, type ChildProcess } from 'node:child_process';
import { mkdir, mkdtemp, writeFile } from 'node:fs/promises';
import { tmpdir } from 'node:os';
import { dirname, join } from 'node:path';
import { promisify } from 'node:util';

const run = promisify(execFile);
/** The repository root. */
export const REPO_ROOT = new URL('../../', import.meta.url).pathname;
/** The repository's pinned Node 24. */
export const NODE24 = join(REPO_ROOT, 'node_modules', '.bin', 'node');

/** An installed copy of the package in a temp project. */
export interface PackedInstall {
  /** The temp folder holding the tarball and the project. */
  root: string;
  tarball: string;
  tarballBytes: number;
  /** The project folder (package.json, node_modules/taos-physics). */
  app: string;
  installMs: number;
}

/** Builds (npm run build), packs and installs into `<tmp>/app`; throws with npm's output on failure. */
export async function packAndInstall(): Promise<PackedInstall> {
  await run(NODE24, [join(REPO_ROOT, 'scripts', 'build-package.ts')], { cwd: REPO_ROOT, maxBuffer: 1 << 24 });
  const root = await mkdtemp(join(tmpdir(), 'taos-package-'));
  const packed = await run('npm', ['pack', '--ignore-scripts', '--json', '--pack-destination', root], { cwd: REPO_ROOT, maxBuffer: 1 << 24 });
  const [info] = JSON.parse(packed.stdout) as Array<{ filename: string; size: number }>;
  const tarball = join(root, info.filename);
  const app = join(root, 'app');
  await mkdir(app);
  await writeFile(join(app, 'package.json'), JSON.stringify({ name: 'my-game', version: '1.0.0', private: true, type: 'module' }, null, 2));
  const t0 = performance.now();
  await run('npm', ['install', '--prefer-offline', '--no-audit', '--no-fund', tarball], { cwd: app, maxBuffer: 1 << 24 });
  return { root, tarball, tarballBytes: info.size, app, installMs: performance.now() - t0 };
}

/** Runs the CLI installed in `installDir` (Node 24) in `cwd`; resolves with its exit code and output. */
export function cliIn(cwd: string, args: readonly string[], installDir = cwd): Promise<{ code: number; stdout: string; stderr: string }> {
  return new Promise((resolve) => {
    const child = spawn(NODE24, [join(installDir, 'node_modules', '.bin', 'taos-physics'), ...args], { cwd, stdio: ['ignore', 'pipe', 'pipe'] });
    let stdout = '';
    let stderr = '';
    child.stdout.on('data', (d: Buffer) => (stdout += d.toString()));
    child.stderr.on('data', (d: Buffer) => (stderr += d.toString()));
    child.on('close', (code) => resolve({ code: code ?? -1, stdout, stderr }));
  });
}

/** Starts `taos-physics serve …` from the install and waits (at most 30 s) for the URL it prints. */
export function serveIn(cwd: string, args: readonly string[]): Promise<RunningServe> {
  return waitForUrl(spawn(NODE24, [join(cwd, 'node_modules', '.bin', 'taos-physics'), 'serve', '--port', '0', ...args], { cwd, stdio: ['ignore', 'pipe', 'pipe'] }));
}

/** Runs `npm start` in `cwd` (its own process group, Node 24 first on PATH, PORT=0) and waits for the URL. */
export function npmStartIn(cwd: string): Promise<RunningServe> {
  const env = { ...process.env, PATH: `${dirname(NODE24)}:${process.env.PATH}`, PORT: '0' };
  return waitForUrl(spawn('npm', ['start'], { cwd, env, detached: true, stdio: ['ignore', 'pipe', 'pipe'] }), true);
}

/** A server process and where it listens. */
export interface RunningServe {
  child: ChildProcess;
  url: string;
  wsUrl: string;
  output: () => string;
}

async function waitForUrl(child: ChildProcess, group = false): Promise<RunningServe> {
  let stdout = '';
  let stderr = '';
  child.stdout!.on('data', (d: Buffer) => (stdout += d.toString()));
  child.stderr!.on('data', (d: Buffer) => (stderr += d.toString()));
  const deadline = performance.now() + 30_000;
  while (!/ws:\/\/\S+\//.test(stdout)) {
    if (performance.now() > deadline || child.exitCode !== null) {
      if (group && child.pid !== undefined && child.exitCode === null) process.kill(-child.pid, 'SIGKILL');
      else child.kill('SIGKILL');
      throw new Error(`serve printed no URL; stderr: ${stderr}`);
    }
    await new Promise((r) => setTimeout(r, 50));
  }
  return { child, url: /(http:\/\/\S+\/)/.exec(stdout)![1], wsUrl: /(ws:\/\/\S+\/)/.exec(stdout)![1], output: () => stdout + stderr };
}

/** Sends SIGTERM (to its process group when it leads one: npm and the server it started) and waits for the exit code. */
export function stop(child: ChildProcess, group = false): Promise<number | null> {
  if (child.exitCode !== null) return Promise.resolve(child.exitCode);
  const exited = new Promise<number | null>((resolve) => child.once('exit', (code) => resolve(code)));
  if (group && child.pid !== undefined) process.kill(-child.pid, 'SIGTERM');
  else child.kill('SIGTERM');
  return exited;
}
