// The investigation probes' shared frame (bench/clients-probe.ts, bench/rooms-probe.ts): the bench server pinned to
// CPU 0 with Node flags of the caller's choice, and one measured window of a light swarm already running on CPU 1,
// with CPU 0's busy share over that window from /proc/stat.
import { spawn } from 'node:child_process';
import { readFileSync } from 'node:fs';
import { fileURLToPath } from 'node:url';
import { nextJson, sendLine, stopChild, REPO_ROOT, type Child } from './child.ts';
import type { ServerReport, SwarmReport } from './server-bench.ts';

const SERVER = fileURLToPath(new URL('../procs/bench-server.ts', import.meta.url));

/** A pinned bench server and everything it printed. */
export interface ProbeServer {
  server: Child;
  wsUrl: string;
  /** Its whole stdout so far. */
  stdout(): string;
}

/** Starts procs/bench-server.ts on CPU 0 with `nodeFlags` before it and `args` after it; resolves once it listens. */
export async function startProbeServer(nodeFlags: readonly string[], args: readonly string[]): Promise<ProbeServer> {
  const proc = spawn('taskset', ['-c', '0', process.execPath, ...nodeFlags, SERVER, ...args], { cwd: REPO_ROOT, stdio: ['pipe', 'pipe', 'inherit'], env: process.env });
  let out = '';
  proc.stdout.setEncoding('utf8').on('data', (d: string) => (out += d));
  const exited = new Promise<number | null>((r) => proc.on('exit', (c) => r(c)));
  const server: Child = { proc, stdout: () => out, stderr: () => '', exited };
  const wsUrl = await nextJson<string>(server, 'wsUrl', 60_000);
  return { server, wsUrl, stdout: () => out };
}

function cpu0Ticks(): number[] {
  return (readFileSync('/proc/stat', 'utf8').split('\n').find((l) => l.startsWith('cpu0 ')) ?? '').trim().split(/\s+/).slice(1).map(Number);
}

/**
 * Measures the swarm's window (it printed 'window' already): marks the server, waits for the swarm's report, takes
 * the server's, then stops both. `cpu0Busy`: CPU 0's busy share over the window, everyone's work together.
 */
export async function measureWindow(probe: ProbeServer, swarm: Child, windowMs: number): Promise<{ bots: SwarmReport; server: ServerReport; cpu0Busy: number }> {
  const { server } = probe;
  const stat0 = cpu0Ticks();
  sendLine(server, 'mark');
  await nextJson(server, 'marked', 30_000);
  const bots = await nextJson<SwarmReport>(swarm, 'report', windowMs + 30_000);
  const stat1 = cpu0Ticks();
  sendLine(server, 'report');
  const report = await nextJson<ServerReport>(server, 'report', 30_000);
  await stopChild(swarm);
  server.proc.stdin!.end();
  await server.exited;
  const d = stat1.map((v, i) => v - stat0[i]);
  const all = d.reduce((a, b) => a + b, 0);
  return { bots, server: report, cpu0Busy: (all - d[3] - d[4]) / all };
}
