// Cost of the gateway's send path: server/ws-gateway.ts's connections (this checkout's, and with --against DIR
// another checkout's, side by side in this process) each send one snapshot-sized message per turn to N ws clients
// in a child process (pinned to CPU 1 where taskset allows; this process to CPU 0 by the caller's taskset if wanted).
// Turns alternate between the sides at 60 per second (each side 30 a second, like 30 Hz snapshots); per side, this
// process's CPU time (process.cpuUsage: the JS, the framing and the write system calls) from the first send of a turn
// to the next macrotask, per client per turn. Run:
// node_modules/.bin/node bench/ws-send-cost.ts [--clients 256] [--turns 600] [--rounds 3] [--bytes 180] [--against DIR]
import { createServer } from 'node:http';
import { loadavg } from 'node:os';
import { join, resolve } from 'node:path';
import { pathToFileURL } from 'node:url';
import WebSocket from 'ws';
import type * as Gateway from '../server/ws-gateway.ts';
import type { ServerConnection } from '../server/connection.ts';
import { SystemClock } from '../server/clock.ts';
import { ConnectionPolicy } from '../server/connection-policy.ts';
import { canPin, nextJson, startNode, stopChild } from './lib/child.ts';
import { median, round } from './lib/stats.ts';

const argv = process.argv.slice(2);
const flag = (name: string): string | undefined => {
  const i = argv.indexOf(`--${name}`);
  return i >= 0 ? argv[i + 1] : undefined;
};

if (argv[0] === '--clients-of') {
  // The child: N sockets to each URL that only count what arrives.
  const urls = argv.slice(2);
  const n = Number(argv[1]);
  let messages = 0;
  const open: Promise<void>[] = [];
  for (const url of urls) {
    for (let i = 0; i < n; i++) {
      const ws = new WebSocket(url, { perMessageDeflate: false });
      ws.on('message', () => void messages++);
      open.push(new Promise((r) => ws.once('open', () => r())));
    }
  }
  await Promise.all(open);
  process.stdout.write(`${JSON.stringify({ open: urls.length * n })}\n`);
  setInterval(() => process.stdout.write(`${JSON.stringify({ messages })}\n`), 1000);
} else {
  const clients = Number(flag('clients') ?? 256);
  const turns = Number(flag('turns') ?? 600);
  const rounds = Number(flag('rounds') ?? 3);
  const bytes = Number(flag('bytes') ?? 180);
  const againstDir = flag('against');
  const roots = [{ name: 'this checkout', root: resolve('.') }, ...(againstDir ? [{ name: againstDir, root: resolve(againstDir) }] : [])];
  const clock = new SystemClock();
  const sides = await Promise.all(
    roots.map(async ({ name, root }) => {
      const gw = (await import(pathToFileURL(join(root, 'server/ws-gateway.ts')).href)) as typeof Gateway;
      const http = createServer();
      const conns: ServerConnection[] = [];
      const gateway = gw.attachWsGateway(http, {
        clock,
        maxPayloadBytes: 1024,
        policy: new ConnectionPolicy(clock, { maxSocketsPerAddress: Infinity, maxPendingPerAddress: Infinity }),
        onConnection: (c) => {
          c.attach({ message: () => {}, close: () => {} });
          conns.push(c);
        },
      });
      await new Promise<void>((r) => http.listen(0, '127.0.0.1', () => r()));
      const port = (http.address() as { port: number }).port;
      return { name, http, gateway, conns, url: `ws://127.0.0.1:${port}`, cpuUs: [] as number[] };
    }),
  );
  const child = startNode(new URL(import.meta.url).pathname, ['--clients-of', String(clients), ...sides.map((s) => s.url)], { cpu: canPin() ? 1 : undefined });
  await nextJson(child, 'open', 120_000);
  const payload = Uint8Array.from({ length: bytes }, (_, i) => (i * 37) & 0xff);
  const macrotask = (): Promise<void> => new Promise((r) => setImmediate(r));
  const load0 = loadavg()[0];
  for (let r = 0; r < rounds; r++) {
    const spent = sides.map(() => 0);
    for (let t = 0; t < turns * sides.length; t++) {
      const k = (t + r) % sides.length;
      const s = sides[k];
      const c0 = process.cpuUsage();
      for (const c of s.conns) c.send(payload);
      await macrotask();
      const c = process.cpuUsage(c0);
      spent[k] += c.user + c.system;
      await new Promise((res) => setTimeout(res, 1000 / 60));
    }
    sides.forEach((s, k) => s.cpuUs.push(spent[k] / turns / s.conns.length));
  }
  const load1 = loadavg()[0];
  await stopChild(child);
  for (const s of sides) {
    await s.gateway.close(100);
    s.http.close();
  }
  const base = sides[1] ? median(sides[1].cpuUs) : null;
  for (const s of sides) {
    const us = median(s.cpuUs);
    process.stdout.write(`${s.name}: ${round(us, 3)} µs CPU per client per turn (rounds: ${s.cpuUs.map((x) => round(x, 3)).join(', ')})${base !== null && s !== sides[1] ? `, ×${round(us / base, 3)} of ${sides[1].name}` : ''}\n`);
  }
  process.stdout.write(`${clients} clients per side, ${bytes}-byte messages, load ${round(load0, 2)} → ${round(load1, 2)}\n`);
}
