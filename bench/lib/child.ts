// Child processes for the benchmarks: run the project's CLI or a bench helper under this Node, wait for output on
// stdout or for exit (each with a time limit), and stop what was started (SIGTERM, then SIGKILL) by its own handle.
import { spawn, spawnSync, type ChildProcess } from 'node:child_process';
import { fileURLToPath } from 'node:url';

/** The repository root. */
export const REPO_ROOT = fileURLToPath(new URL('../../', import.meta.url));
/** The CLI entry (bin/taos-physics.js). */
export const CLI_PATH = fileURLToPath(new URL('../../bin/taos-physics.js', import.meta.url));

/** A started child with its output collected. */
export interface Child {
  proc: ChildProcess;
  stdout(): string;
  stderr(): string;
  /** Resolves with the exit code (null when killed by a signal). */
  exited: Promise<number | null>;
}

let tasksetWorks: boolean | null = null;

/** Whether `taskset` can pin a process to a CPU here (it execs the command, so the child's pid stays Node's). */
export function canPin(): boolean {
  tasksetWorks ??= spawnSync('taskset', ['-c', '0', 'true'], { stdio: 'ignore' }).status === 0;
  return tasksetWorks;
}

/**
 * Starts `node script args…` with this process's Node (stdout/stderr collected; stdin ignored unless piped; extra
 * env); `cpu` pins it to that CPU with taskset (check canPin() first).
 */
export function startNode(script: string, args: readonly string[], opts: { stdin?: boolean; env?: Record<string, string>; cpu?: number } = {}): Child {
  const env = opts.env ? { ...process.env, ...opts.env } : process.env;
  const argv = [script, ...args];
  const [command, commandArgs] = opts.cpu === undefined ? [process.execPath, argv] : ['taskset', ['-c', String(opts.cpu), process.execPath, ...argv]];
  const proc = spawn(command, commandArgs, { cwd: REPO_ROOT, stdio: [opts.stdin ? 'pipe' : 'ignore', 'pipe', 'pipe'], env });
  let out = '';
  let err = '';
  proc.stdout!.setEncoding('utf8').on('data', (d: string) => (out += d));
  proc.stderr!.setEncoding('utf8').on('data', (d: string) => (err += d));
  const exited = new Promise<number | null>((resolve) => proc.on('exit', (code) => resolve(code)));
  return { proc, stdout: () => out, stderr: () => err, exited };
}

/**
 * Waits until `test(stdout)` returns a value; resolves with it and the performance.now() of the chunk that made it
 * true. Throws when the child exits first or after `timeoutMs`.
 */
export function waitForOutput<T>(child: Child, test: (stdout: string) => T | null, timeoutMs: number, what: string): Promise<{ value: T; atMs: number }> {
  return new Promise((resolve, reject) => {
    let timer: ReturnType<typeof setTimeout> | null = null;
    const finish = (): void => {
      if (timer) clearTimeout(timer);
      child.proc.stdout!.off('data', check);
      child.proc.off('exit', onExit);
    };
    function check(): boolean {
      const value = test(child.stdout());
      if (value === null) return false;
      finish();
      resolve({ value, atMs: performance.now() });
      return true;
    }
    function onExit(): void {
      if (check()) return;
      finish();
      reject(new Error(`the child exited before ${what}: ${child.stderr().trim().slice(-600)}`));
    }
    if (check()) return;
    timer = setTimeout(() => {
      finish();
      reject(new Error(`no ${what} within ${timeoutMs} ms: ${child.stderr().trim().slice(-600)}`));
    }, timeoutMs);
    // Registered after the collector in startNode, so child.stdout() already holds the new chunk.
    child.proc.stdout!.on('data', check);
    child.proc.on('exit', onExit);
  });
}

/** Waits until stdout matches `re`; resolves with the match and when it arrived. */
export async function waitForLine(child: Child, re: RegExp, timeoutMs: number): Promise<{ match: RegExpMatchArray; atMs: number }> {
  const r = await waitForOutput(child, (text) => text.match(re), timeoutMs, `a line matching ${re}`);
  return { match: r.value, atMs: r.atMs };
}

const consumed = new WeakMap<Child, number>();

/** The value of `key` in the next JSON line on stdout that has it (lines before it, and non-JSON lines, are passed over). */
export async function nextJson<T>(child: Child, key: string, timeoutMs: number): Promise<T> {
  const find = (text: string): { value: T; end: number } | null => {
    let from = consumed.get(child) ?? 0;
    for (;;) {
      const nl = text.indexOf('\n', from);
      if (nl < 0) return null;
      const line = text.slice(from, nl).trim();
      from = nl + 1;
      if (!line.startsWith('{')) continue;
      try {
        const obj = JSON.parse(line) as Record<string, unknown>;
        if (key in obj) return { value: obj[key] as T, end: from };
      } catch {
        // not JSON: pass over it
      }
    }
  };
  const hit = (await waitForOutput(child, find, timeoutMs, `a JSON line with "${key}"`)).value;
  consumed.set(child, hit.end);
  return hit.value;
}

/** Writes one line to the child's stdin (started with stdin: true). */
export function sendLine(child: Child, line: string): void {
  if (!child.proc.stdin) throw new Error('sendLine: the child was started without a stdin pipe');
  child.proc.stdin.write(`${line}\n`);
}

/** Runs a child to completion within `timeoutMs`; throws with its stderr when it fails. */
export async function runToEnd(child: Child, timeoutMs: number, what: string): Promise<string> {
  const timer = setTimeout(() => child.proc.kill('SIGKILL'), timeoutMs);
  const code = await child.exited;
  clearTimeout(timer);
  if (code !== 0) throw new Error(`${what} failed (exit ${code}): ${child.stderr().trim().slice(-800)}`);
  return child.stdout();
}

/** Stops a child: SIGTERM, then SIGKILL after `graceMs`. Resolves once it has exited. */
export async function stopChild(child: Child, graceMs = 5000): Promise<void> {
  if (child.proc.exitCode !== null || child.proc.signalCode !== null) return;
  child.proc.kill('SIGTERM');
  const timer = setTimeout(() => child.proc.kill('SIGKILL'), graceMs);
  await child.exited;
  clearTimeout(timer);
}
