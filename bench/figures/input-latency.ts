// Input latency: the real server (startServer: HTTP + ws on loopback, 60 Hz snapshots) in this process, one client
// library player in another. Server side: for every input, ticks from its first arrival to the tick that applies it.
// Client side: round trip from an input leaving the socket to its effect showing in a snapshot.
import { fileURLToPath } from 'node:url';
import { DEFAULT_SCENARIO } from '../../scenarios/index.ts';
import { silentLogger } from '../../server/logger.ts';
import { createMetrics } from '../../server/metrics.ts';
import { startServer } from '../../server/start-server.ts';
import type { InputCommand } from '../../shared/sim/input.ts';
import { TICK_MS } from '../../shared/tick-rate.ts';
import { runToEnd, startNode } from '../lib/child.ts';
import type { FigureImpl, FigureOutput } from '../lib/figure.ts';
import { round, roundSummary, summarize } from '../lib/stats.ts';

const GOAL_TICKS = 1;
const SNAPSHOT_RATE_HZ = 60;
const CLIENT = fileURLToPath(new URL('../procs/latency-client.ts', import.meta.url));

interface ClientReport {
  playerId: number;
  samples: Array<{ sentMs: number; inputTick: number; serverTickAtSend: number; seenMs: number | null; seenTick: number | null }>;
  leadTicks: number | null;
  rttMs: number | null;
  missedInputTicks: number | null;
}

async function run(opts: { quick: boolean; log(m: string): void }): Promise<FigureOutput> {
  const toggles = opts.quick ? 15 : 50;
  const intervalMs = 300;
  const server = await startServer({ port: 0, host: '127.0.0.1', scenario: DEFAULT_SCENARIO, snapshotRateHz: SNAPSHOT_RATE_HZ, logger: silentLogger(), metrics: createMetrics({ processMetrics: false }) });
  try {
    const room = server.game.rooms.get('default');
    if (!room) throw new Error('input latency: the server has no default room');
    // First arrival of each (player, tick) input: the room's tick counter then (ticks applied so far) and the time.
    // Messages repeat the last few inputs, so later copies of a tick (even after it was applied) are not arrivals.
    const arrivals = new Map<number, Map<number, { ticksApplied: number; atMs: number }>>();
    let late = 0;
    const offer = room.offerInput.bind(room);
    room.offerInput = (playerId: number, tick: number, command: InputCommand) => {
      let byPlayer = arrivals.get(tick);
      if (!byPlayer) arrivals.set(tick, (byPlayer = new Map()));
      if (!byPlayer.has(playerId)) {
        byPlayer.set(playerId, { ticksApplied: room.sim.tick, atMs: performance.now() });
        if (tick < room.sim.tick) late++;
      }
      return offer(playerId, tick, command);
    };
    const waitTicks: number[] = [];
    const waitMs: number[] = [];
    room.onTick((record) => {
      const now = performance.now();
      const byPlayer = arrivals.get(record.tick);
      for (const c of record.commands) {
        const a = byPlayer?.get(c.playerId);
        // Applied by the next tick run after arrival = 1; each tick of lead the client chose adds one.
        if (a) {
          waitTicks.push(record.tick - a.ticksApplied + 1);
          waitMs.push(now - a.atMs);
        }
      }
      for (const t of arrivals.keys()) if (t < record.tick - 120) arrivals.delete(t);
    });
    opts.log(`client: ${toggles} toggles of the Use button, ${intervalMs} ms apart, ${SNAPSHOT_RATE_HZ} Hz snapshots`);
    const out = await runToEnd(startNode(CLIENT, [server.wsUrl, String(toggles), String(intervalMs)]), 60_000 + toggles * intervalMs, 'latency client');
    const report = JSON.parse(out.trim().split('\n').at(-1)!) as ClientReport;
    const seen = report.samples.filter((s) => s.sentMs >= 0 && s.seenMs !== null);
    if (waitTicks.length === 0 || seen.length === 0) throw new Error(`input latency: no samples (server ${waitTicks.length}, client ${seen.length} of ${report.samples.length})`);
    const ticks = summarize(waitTicks);
    const ms = summarize(waitMs);
    const rtt = summarize(seen.map((s) => s.seenMs! - s.sentMs));
    const rttTicks = summarize(seen.map((s) => s.seenTick! - s.inputTick));
    const histogram: Record<string, number> = {};
    for (const t of waitTicks) histogram[String(t)] = (histogram[String(t)] ?? 0) + 1;
    return {
      headline: { inputLatencyTicks: round(ticks.median, 2) },
      detail: {
        scenario: DEFAULT_SCENARIO,
        snapshotRateHz: SNAPSHOT_RATE_HZ,
        inputs: waitTicks.length,
        arrivalToApplyTicks: roundSummary(ticks, 2),
        arrivalToApplyTicksHistogram: histogram,
        arrivalToApplyMs: roundSummary(ms, 3),
        lateInputs: late,
        inputToSnapshotMs: roundSummary(rtt, 2),
        inputTickToSnapshotTick: roundSummary(rttTicks, 2),
        effectSamples: seen.length,
        clientLeadTicks: report.leadTicks,
        clientRttMs: report.rttMs,
        missedInputTicks: report.missedInputTicks,
      },
      rows: [
        { figure: 'input latency', measure: `arrival → applying tick (median of ${waitTicks.length} inputs)`, value: ticks.median, unit: 'ticks', digits: 1, goal: { op: '<=', value: GOAL_TICKS } },
        { figure: 'input latency', measure: 'arrival → applying tick (p99)', value: ticks.p99, unit: 'ticks', digits: 1 },
        { figure: 'input latency', measure: `input sent → effect in a snapshot, loopback (median of ${seen.length})`, value: rtt.median, unit: 'ms', digits: 1 },
        { figure: 'input latency', measure: 'input sent → effect in a snapshot (p99)', value: rtt.p99, unit: 'ms', digits: 1 },
      ],
      charts: [
        {
          title: 'Input latency on loopback (ms)',
          unit: 'ms',
          bars: [
            { label: 'arrival → applied (median)', value: ms.median, series: 'ours' },
            { label: 'arrival → applied (p99)', value: ms.p99, series: 'ours' },
            { label: 'sent → seen in snapshot (median)', value: rtt.median, series: 'other' },
            { label: 'sent → seen in snapshot (p99)', value: rtt.p99, series: 'other' },
            { label: 'one tick', value: TICK_MS, series: 'raw' },
          ],
        },
      ],
      notes: [
        `The server (startServer, ${DEFAULT_SCENARIO}, ${SNAPSHOT_RATE_HZ} Hz snapshots) runs in the figure's process; the client library (sdk/, Node's WebSocket) runs in a child process on loopback.`,
        'Arrival → applying tick: 1 means the input was applied by the first tick that ran after it arrived; every tick of input lead the client chose (to absorb jitter) adds one. Counted at the first arrival of each (player, tick) input (messages repeat recent inputs).',
        `Sent → seen: the client toggles its Use button every ${intervalMs} ms; from the first input message carrying the new state leaving the socket to the first decoded snapshot whose own character shows it.`,
        `Client lead at the end: ${report.leadTicks} tick(s); RTT ${report.rttMs === null ? 'n/a' : report.rttMs.toFixed(2)} ms; inputs that arrived late: ${late}.`,
      ],
    };
  } finally {
    await server.close('bench done');
  }
}

/** The input-latency figure. */
export const figure: FigureImpl = { run };
