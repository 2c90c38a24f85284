// The clients-per-core figure's bot process: N players on the client library (sdk/ over Node's WebSocket), each
// steered every tick by a scripted bot (walk, turn, sprint, jump; no firing, so the scene keeps its body count). Prints
// {"ready"} once all are welcomed, {"window"} after SETTLE_MS, then {"report"} after WINDOW_MS; it plays on until stopped.
// Run: node bench/procs/bot-swarm.ts WS_URL CLIENTS SETTLE_MS WINDOW_MS
import { connect, type NetClient } from '../lib/client-lib.ts';
import { BotScript } from '../../shared/sim/bots.ts';
import { TICK_MS } from '../../shared/tick-rate.ts';

const [url, nArg, settleArg, windowArg] = process.argv.slice(2);
const n = Number(nArg);
const settleMs = Number(settleArg);
const windowMs = Number(windowArg);
if (!url || !Number.isInteger(n) || n < 1 || !(settleMs >= 0) || !(windowMs > 0)) {
  process.stderr.write('usage: node bench/procs/bot-swarm.ts WS_URL CLIENTS SETTLE_MS WINDOW_MS\n');
  process.exit(2);
}
const say = (obj: unknown): void => void process.stdout.write(`${JSON.stringify(obj)}\n`);

const clients: NetClient[] = [];
let protocolErrors = 0;
const CONNECT_BATCH = 16;
for (let i = 0; i < n; i += CONNECT_BATCH) {
  const batch: NetClient[] = [];
  for (let j = i; j < Math.min(n, i + CONNECT_BATCH); j++) {
    const c = connect(url, { name: `swarm-${j + 1}`, reconnect: false });
    c.on('protocolError', () => protocolErrors++);
    batch.push(c);
  }
  await Promise.all(batch.map((c) => c.whenConnected()));
  clients.push(...batch);
}
say({ ready: clients.length });

const script = new BotScript({ seed: 7, bots: n, joinTicks: clients.map(() => 0), fire: false });
const steer = setInterval(() => {
  const record = script.next();
  for (let i = 0; i < record.commands.length; i++) clients[i].setInput(record.commands[i].input);
}, TICK_MS);

const totals = (): { snapshots: number; failed: number; bytesIn: number; bytesOut: number; closed: number } => {
  let snapshots = 0;
  let failed = 0;
  let bytesIn = 0;
  let bytesOut = 0;
  let closed = 0;
  for (const c of clients) {
    const s = c.stats();
    snapshots += s.snapshots;
    failed += s.snapshotsFailed;
    bytesIn += s.bytesIn;
    bytesOut += s.bytesOut;
    if (c.state === 'closed') closed++;
  }
  return { snapshots, failed, bytesIn, bytesOut, closed };
};

await new Promise((r) => setTimeout(r, settleMs));
const start = { atMs: performance.now(), cpu: process.cpuUsage(), ...totals() };
say({ window: true });
await new Promise((r) => setTimeout(r, windowMs));
const end = totals();
const seconds = (performance.now() - start.atMs) / 1000;
const cpu = process.cpuUsage(start.cpu);
say({
  report: {
    clients: n,
    seconds,
    snapshotsPerClientPerSecond: (end.snapshots - start.snapshots) / n / seconds,
    failedSnapshots: end.failed - start.failed,
    kbpsPerClient: ((end.bytesIn - start.bytesIn) * 8) / 1000 / n / seconds,
    kbpsUpPerClient: ((end.bytesOut - start.bytesOut) * 8) / 1000 / n / seconds,
    closedClients: end.closed,
    protocolErrors,
    cpuShare: (cpu.user + cpu.system) / 1e6 / seconds,
  },
});
// Stay connected and playing while the server reports its side of the window (the figure then stops this process).
setTimeout(() => {
  clearInterval(steer);
  for (const c of clients) c.close();
  setTimeout(() => process.exit(0), 500).unref();
}, 5000);
