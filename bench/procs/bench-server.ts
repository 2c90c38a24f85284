// The clients-per-core figure's server process: startServer (HTTP + ws on loopback, the scene's default room, 30 Hz
// snapshots) with the connection caps (total and per address) lifted, every room tick timed. Prints {"wsUrl"} when
// listening; stdin commands: "mark" starts a measurement window, "report" prints the window's tick times and snapshot
// counts as one JSON line.
// Run: node bench/procs/bench-server.ts SCENARIO PARAMS_JSON SNAPSHOT_HZ MAX_CLIENTS
import { createInterface } from 'node:readline';
import { silentLogger } from '../../server/logger.ts';
import { createMetrics } from '../../server/metrics.ts';
import { startServer } from '../../server/start-server.ts';

const [scenario, paramsJson, rateArg, maxArg] = process.argv.slice(2);
const snapshotRateHz = Number(rateArg);
const maxClients = Number(maxArg);
if (!scenario || !paramsJson || !Number.isInteger(snapshotRateHz) || !Number.isInteger(maxClients)) {
  process.stderr.write('usage: node bench/procs/bench-server.ts SCENARIO PARAMS_JSON SNAPSHOT_HZ MAX_CLIENTS\n');
  process.exit(2);
}

const metrics = createMetrics({ processMetrics: false });
const server = await startServer({
  port: 0,
  host: '127.0.0.1',
  scenario,
  params: JSON.parse(paramsJson) as Record<string, number>,
  snapshotRateHz,
  maxClients,
  maxConnections: maxClients + 16,
  // Every bot comes from 127.0.0.1: lift the per-address connection caps.
  connectionPolicy: { maxSocketsPerAddress: Infinity, maxPendingPerAddress: Infinity },
  logger: silentLogger(),
  metrics,
});
const room = server.game.rooms.get('default');
if (!room) throw new Error('bench-server: no default room');

let tickMs: number[] = [];
const tickOnce = room.tickOnce.bind(room);
room.tickOnce = () => {
  const t0 = performance.now();
  tickOnce();
  tickMs.push(performance.now() - t0);
};

async function counter(c: { get(): Promise<{ values: Array<{ value: number }> }> }): Promise<number> {
  return (await c.get()).values.reduce((s, v) => s + v.value, 0);
}

async function counters(): Promise<{ sent: number; skipped: number; ticksSkipped: number; overruns: number }> {
  return {
    sent: await counter(metrics.snapshotsSent),
    skipped: await counter(metrics.snapshotsSkipped),
    ticksSkipped: await counter(metrics.ticksSkipped),
    overruns: await counter(metrics.tickOverruns),
  };
}

let mark = { atMs: performance.now(), cpu: process.cpuUsage(), ...(await counters()) };
const lines = createInterface({ input: process.stdin });
lines.on('line', (line) => {
  void (async () => {
    if (line === 'mark') {
      tickMs = [];
      mark = { atMs: performance.now(), cpu: process.cpuUsage(), ...(await counters()) };
    } else if (line === 'report') {
      const now = await counters();
      const cpu = process.cpuUsage(mark.cpu);
      const seconds = (performance.now() - mark.atMs) / 1000;
      process.stdout.write(
        `${JSON.stringify({
          report: {
            seconds,
            tickMs,
            clients: room.clientCount,
            bodies: room.info().bodies,
            snapshotsSent: now.sent - mark.sent,
            snapshotsSkipped: now.skipped - mark.skipped,
            ticksSkipped: now.ticksSkipped - mark.ticksSkipped,
            overruns: now.overruns - mark.overruns,
            cpuShare: (cpu.user + cpu.system) / 1e6 / seconds,
          },
        })}\n`,
      );
    }
  })();
});
lines.on('close', () => void server.close('bench done').then(() => process.exit(0)));
process.on('SIGTERM', () => void server.close('bench done').then(() => process.exit(0)));
process.stdout.write(`${JSON.stringify({ wsUrl: server.wsUrl })}\n`);
