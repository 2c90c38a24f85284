// Child process of the connection-storm test: N hostile sockets from one loopback address, each reconnecting the moment
// it is refused, cut or kicked. A third sit idle without a hello, a third send garbage until kicked, a third say hello
// and flood pings until kicked. Runs until stdin closes or the time is up; prints its counters as one JSON line.
// Run: node tests/server/storm-probe.ts ws://127.0.0.1:PORT/ [--sockets 300] [--seconds 30] [--from 127.0.0.1]
//      [--kinds idle,garbage,flood]
import { encodeClientMessage, PROTOCOL_VERSION } from '../../shared/protocol/index.ts';
import { maskedFrame, openRawWs, type RawWs } from './raw-ws.ts';

function arg(name: string, fallback: string): string {
  const i = process.argv.indexOf(`--${name}`);
  return i >= 0 && i + 1 < process.argv.length ? process.argv[i + 1] : fallback;
}

const url = process.argv[2];
if (!url?.startsWith('ws://')) throw new Error('usage: node tests/server/storm-probe.ts ws://HOST:PORT/ [--sockets N] [--seconds S] [--from ADDR]');
const sockets = Number(arg('sockets', '300'));
const seconds = Number(arg('seconds', '30'));
const from = arg('from', '127.0.0.1');

type Kind = 'idle' | 'garbage' | 'flood';
const counts = { attempts: 0, upgraded: 0, refused429: 0, refused503: 0, otherStatus: 0, failedToConnect: 0, closedAfterUpgrade: 0, byIdle: 0, byGarbage: 0, byFlood: 0 };
const garbage = maskedFrame(Uint8Array.of(0xc1, 0xc1, 0xc1, 0xc1)); // 0xc1 is never valid msgpack
const hello = maskedFrame(encodeClientMessage({ type: 'hello', version: PROTOCOL_VERSION, name: 'storm', room: null }));
const ping = maskedFrame(encodeClientMessage({ type: 'ping', clientTimeMs: 1 }));
const pingBurst = Buffer.concat(Array.from({ length: 100 }, () => ping));
let stopping = false;

function behave(kind: Kind, ws: RawWs): void {
  if (kind === 'idle') return; // the server's hello deadline ends it
  const burst = kind === 'garbage' ? Buffer.concat(Array.from({ length: 20 }, () => garbage)) : Buffer.concat([hello, pingBurst]);
  ws.socket.write(burst);
  if (kind === 'flood') {
    const timer = setInterval(() => {
      if (ws.closed || ws.socket.destroyed || stopping) clearInterval(timer);
      else ws.socket.write(pingBurst);
    }, 10);
  }
}

async function hostile(kind: Kind): Promise<void> {
  while (!stopping) {
    counts.attempts++;
    let ws: RawWs;
    try {
      ws = await openRawWs(url, { localAddress: from, timeoutMs: 10_000 });
    } catch {
      counts.failedToConnect++;
      await new Promise((r) => setImmediate(r));
      continue;
    }
    if (ws.status !== 101) {
      if (ws.status === 429) counts.refused429++;
      else if (ws.status === 503) counts.refused503++;
      else counts.otherStatus++;
      ws.socket.destroy();
      continue;
    }
    counts.upgraded++;
    if (kind === 'idle') counts.byIdle++;
    else if (kind === 'garbage') counts.byGarbage++;
    else counts.byFlood++;
    behave(kind, ws);
    await new Promise<void>((resolve) => {
      if (ws.closed) resolve();
      else ws.socket.once('close', () => resolve());
    });
    counts.closedAfterUpgrade++;
  }
}

const kinds = arg('kinds', 'idle,garbage,flood').split(',') as Kind[];
if (kinds.length === 0 || kinds.some((k) => k !== 'idle' && k !== 'garbage' && k !== 'flood')) throw new Error('--kinds takes idle, garbage and/or flood');
const started = performance.now();
const runs = Array.from({ length: sockets }, (_, i) => hostile(kinds[i % kinds.length]));
const stop = (): void => {
  stopping = true;
};
process.stdin.on('end', stop);
process.stdin.on('close', stop);
process.stdin.resume();
setTimeout(stop, seconds * 1000).unref();
await Promise.race([Promise.all(runs), new Promise((r) => setTimeout(r, seconds * 1000 + 12_000))]);
process.stdout.write(`${JSON.stringify({ sockets, seconds: (performance.now() - started) / 1000, ...counts })}\n`);
process.exit(0);
