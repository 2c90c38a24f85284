// Input latency: the real server (startServer: HTTP + ws on loopback, 60 Hz snapshots) in this process, one client
// library player in another. Server side: for every input, ticks from its first arrival to the tick that applies it,
// with the inputs never applied (late, dropped) kept in the distribution. Client side: round trip from an input
// leaving the socket to its effect showing in a snapshot.
import { fileURLToPath } from 'node:url';
import { DEFAULT_SCENARIO } from '../../scenarios/index.ts';
import { OfferResult } from '../../server/input-buffer.ts';
import { silentLogger } from '../../server/logger.ts';
import { createMetrics } from '../../server/metrics.ts';
import { startServer } from '../../server/start-server.ts';
import type { InputCommand } from '../../shared/sim/input.ts';
import { TICK_MS } from '../../shared/tick-rate.ts';
import { runToEnd, startNode } from '../lib/child.ts';
import type { FigureImpl, FigureOutput } from '../lib/figure.ts';
import { latencyDistribution } from '../lib/rules.ts';
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
    const room = server.game.rooms.local('default');
    if (!room) throw new Error('input latency: the server has no default room');
    // First arrival of each (player, tick) input: the room's tick counter then (ticks applied so far), the time, and
    // whether any copy was stored. Messages repeat the last few inputs, so later copies are not arrivals (but one of
    // them may be the copy that gets stored, when the first was too far ahead).
    const arrivals = new Map<number, Map<number, { ticksApplied: number; atMs: number; stored: boolean; counted: boolean }>>();
    let late = 0;
    let notApplied = 0;
    const offer = room.offerInput.bind(room);
    room.offerInput = (playerId: number, tick: number, command: InputCommand) => {
      const ticksApplied = room.sim.tick;
      const result = offer(playerId, tick, command);
      let byPlayer = arrivals.get(tick);
      if (!byPlayer) arrivals.set(tick, (byPlayer = new Map()));
      const a = byPlayer.get(playerId);
      if (!a) {
        // Its tick already ran (with the previous command repeated): this input will never be applied.
        const tooLate = tick < ticksApplied;
        byPlayer.set(playerId, { ticksApplied, atMs: performance.now(), stored: result === OfferResult.Accepted, counted: tooLate });
        if (tooLate) {
          late++;
          notApplied++;
        }
      } else if (result === OfferResult.Accepted) a.stored = true;
      return result;
    };
    // A message's commands arrive through offerInputs (one player lookup per message): each goes through the timed
    // offerInput above, and the session's tally counts as the room's own offerInputs would.
    room.offerInputs = (playerId, firstTick, commands, tally) => {
      for (let i = 0; i < commands.length; i++) {
        const result = room.offerInput(playerId, firstTick + i, commands[i]);
        if (result === OfferResult.Late) tally.inputsLate++;
        else if (result === OfferResult.TooFar) tally.inputsTooFar++;
      }
    };
    const waitTicks: number[] = [];
    const waitMs: number[] = [];
    room.onTick((record) => {
      const now = performance.now();
      const byPlayer = arrivals.get(record.tick);
      for (const c of record.commands) {
        const a = byPlayer?.get(c.playerId);
        if (!a || a.counted) continue;
        a.counted = true;
        // Applied by the next tick run after arrival = 1; each tick of lead the client chose adds one.
        if (a.stored) {
          waitTicks.push(record.tick - a.ticksApplied + 1);
          waitMs.push(now - a.atMs);
        } else notApplied++; // arrived in time, but no copy was stored (too far ahead): the tick repeated the old command
      }
      for (const t of arrivals.keys()) if (t < record.tick - 120) arrivals.delete(t);
    });
    opts.log(`client: ${toggles} toggles of the Use button, ${intervalMs} ms apart, ${SNAPSHOT_RATE_HZ} Hz snapshots`);
    const out = await runToEnd(startNode(CLIENT, [server.wsUrl, String(toggles), String(intervalMs)]), 60_000 + toggles * intervalMs, 'latency client');
    const report = JSON.parse(out.trim().split('\n').at(-1)!) as ClientReport;
    const seen = report.samples.filter((s) => s.sentMs >= 0 && s.seenMs !== null);
    if (waitTicks.length === 0 || seen.length === 0) throw new Error(`input latency: no samples (server ${waitTicks.length}, client ${seen.length} of ${report.samples.length})`);
    const dist = latencyDistribution(waitTicks, notApplied);
    const ms = summarize(waitMs);
    const rtt = summarize(seen.map((s) => s.seenMs! - s.sentMs));
    const rttTicks = summarize(seen.map((s) => s.seenTick! - s.inputTick));
    const lateText = (v: number | null): string => (v === null ? ' (lands on an input never applied)' : '');
    return {
      headline: { inputLatencyTicks: dist.median === null ? null : round(dist.median, 2) },
      detail: {
        scenario: DEFAULT_SCENARIO,
        snapshotRateHz: SNAPSHOT_RATE_HZ,
        inputs: dist.inputs,
        applied: dist.applied,
        notApplied: dist.notApplied,
        notAppliedShare: round(dist.notAppliedShare, 4),
        lateInputs: late,
        arrivalToApplyTicks: { median: dist.median, p90: dist.p90, p99: dist.p99, max: dist.max },
        arrivalToApplyTicksHistogram: dist.histogram,
        arrivalToApplyMsOfApplied: roundSummary(ms, 3),
        inputToSnapshotMs: roundSummary(rtt, 2),
        inputTickToSnapshotTick: roundSummary(rttTicks, 2),
        effectSamples: seen.length,
        clientLeadTicks: report.leadTicks,
        clientRttMs: report.rttMs,
        missedInputTicks: report.missedInputTicks,
      },
      rows: [
        { figure: 'input latency', measure: `arrival → applying tick (median of ${dist.inputs} inputs, late ones included)${lateText(dist.median)}`, value: dist.median, unit: 'ticks', digits: 1, goal: { op: '<=', value: GOAL_TICKS } },
        { figure: 'input latency', measure: `arrival → applying tick (p99)${lateText(dist.p99)}`, value: dist.p99, unit: 'ticks', digits: 1 },
        { figure: 'input latency', measure: `inputs never applied (late: their tick had run; or dropped), of ${dist.inputs}`, value: dist.notAppliedShare * 100, unit: '%', digits: 2 },
        { figure: 'input latency', measure: `input sent → effect in a snapshot, loopback (median of ${seen.length})`, value: rtt.median, unit: 'ms', digits: 1 },
        { figure: 'input latency', measure: 'input sent → effect in a snapshot (p99)', value: rtt.p99, unit: 'ms', digits: 1 },
      ],
      charts: [
        {
          title: 'Input latency on loopback (ms)',
          unit: 'ms',
          bars: [
            { label: 'arrival → applied (median of applied)', value: ms.median, series: 'ours' },
            { label: 'arrival → applied (p99 of applied)', value: ms.p99, series: 'ours' },
            { label: 'sent → seen in snapshot (median)', value: rtt.median, series: 'other' },
            { label: 'sent → seen in snapshot (p99)', value: rtt.p99, series: 'other' },
            { label: 'one tick', value: TICK_MS, series: 'raw' },
          ],
        },
      ],
      notes: [
        `The server (startServer, ${DEFAULT_SCENARIO}, ${SNAPSHOT_RATE_HZ} Hz snapshots) runs in the figure's process; the client library (sdk/, Node's WebSocket) runs in a child process on loopback.`,
        'Arrival → applying tick: 1 means the input was applied by the first tick that ran after it arrived; every tick of input lead the client chose (to absorb jitter) adds one. Counted at the first arrival of each (player, tick) input (messages repeat recent inputs).',
        `Inputs never applied count in the distribution, ranked after the slowest applied one: ${late} arrived after their tick had run (the server repeated the previous command), ${notApplied - late} were dropped (too far ahead, no later copy stored). A quantile that lands on them has no value (n/a). The ms chart covers applied inputs only.`,
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
