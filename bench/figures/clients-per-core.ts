// Clients per core: a server process (startServer, ~300-body shape-rain, 60 Hz tick, 30 Hz snapshots) and a bot
// process (N client-library players on loopback WebSockets). N climbs a ladder until a window's tick p99 exceeds
// 16.7 ms or more than 1% of snapshots are skipped; the largest passing N is the figure.
import { fileURLToPath } from 'node:url';
import { TICK_MS } from '../../shared/tick-rate.ts';
import { nextJson, sendLine, startNode, stopChild, type Child } from '../lib/child.ts';
import type { FigureImpl, FigureOutput } from '../lib/figure.ts';
import { CROWD_SCENE } from '../lib/scenes.ts';
import { quantile, round } from '../lib/stats.ts';

const GOAL = 256;
const TICK_BUDGET_MS = TICK_MS;
const MAX_SKIPPED_SHARE = 0.01;
const SNAPSHOT_RATE_HZ = 30;
const SERVER = fileURLToPath(new URL('../procs/bench-server.ts', import.meta.url));
const SWARM = fileURLToPath(new URL('../procs/bot-swarm.ts', import.meta.url));

interface ServerReport {
  seconds: number;
  tickMs: number[];
  clients: number;
  bodies: number;
  snapshotsSent: number;
  snapshotsSkipped: number;
  ticksSkipped: number;
  overruns: number;
  cpuShare: number;
}

interface SwarmReport {
  clients: number;
  seconds: number;
  snapshotsPerClientPerSecond: number;
  failedSnapshots: number;
  kbpsPerClient: number;
  closedClients: number;
  protocolErrors: number;
  cpuShare: number;
}

interface Step {
  clients: number;
  pass: boolean;
  why: string;
  ticks: number;
  tickP50Ms: number;
  tickP90Ms: number;
  tickP99Ms: number;
  tickMaxMs: number;
  /** Ticks over the 16.7 ms budget in the window. */
  ticksOverBudget: number;
  ticksPerSecond: number;
  snapshotsSkippedShare: number;
  slowdownTicks: number;
  serverCpuShare: number;
  botCpuShare: number;
  snapshotsPerClientPerSecond: number;
  kbpsPerClient: number;
  bodies: number;
}

async function step(server: Child, wsUrl: string, clients: number, settleMs: number, windowMs: number): Promise<Step> {
  const swarm = startNode(SWARM, [wsUrl, String(clients), String(settleMs), String(windowMs)]);
  try {
    await nextJson<number>(swarm, 'ready', 60_000 + clients * 200);
    await nextJson<boolean>(swarm, 'window', settleMs + 30_000);
    sendLine(server, 'mark');
    const bots = await nextJson<SwarmReport>(swarm, 'report', windowMs + 30_000);
    sendLine(server, 'report');
    const s = await nextJson<ServerReport>(server, 'report', 30_000);
    const ticks = s.tickMs.length;
    const p99 = ticks > 0 ? quantile(s.tickMs, 0.99) : Infinity;
    const offered = s.snapshotsSent + s.snapshotsSkipped;
    const skippedShare = offered > 0 ? s.snapshotsSkipped / offered : 1;
    const reasons: string[] = [];
    if (!(p99 <= TICK_BUDGET_MS)) reasons.push(`tick p99 ${p99.toFixed(1)} ms > ${TICK_BUDGET_MS.toFixed(1)} ms`);
    if (skippedShare > MAX_SKIPPED_SHARE) reasons.push(`${(skippedShare * 100).toFixed(1)}% of snapshots skipped`);
    if (bots.closedClients > 0) reasons.push(`${bots.closedClients} clients dropped`);
    return {
      clients,
      pass: reasons.length === 0,
      why: reasons.join('; '),
      ticks,
      tickP50Ms: round(ticks > 0 ? quantile(s.tickMs, 0.5) : NaN, 3),
      tickP90Ms: round(ticks > 0 ? quantile(s.tickMs, 0.9) : NaN, 3),
      tickP99Ms: round(p99, 3),
      tickMaxMs: round(ticks > 0 ? Math.max(...s.tickMs) : NaN, 3),
      ticksOverBudget: s.tickMs.filter((ms) => ms > TICK_BUDGET_MS).length,
      ticksPerSecond: round(ticks / s.seconds, 1),
      snapshotsSkippedShare: round(skippedShare, 4),
      slowdownTicks: s.ticksSkipped,
      serverCpuShare: round(s.cpuShare, 2),
      botCpuShare: round(bots.cpuShare, 2),
      snapshotsPerClientPerSecond: round(bots.snapshotsPerClientPerSecond, 1),
      kbpsPerClient: round(bots.kbpsPerClient, 1),
      bodies: s.bodies,
    };
  } finally {
    await stopChild(swarm);
  }
}

async function run(opts: { quick: boolean; log(m: string): void }): Promise<FigureOutput> {
  const ladder = opts.quick ? [16, 32, 64, 128, 256] : [8, 16, 32, 48, 64, 96, 128, 192, 256, 320, 384, 512];
  const settleMs = opts.quick ? 1000 : 3000;
  const windowMs = opts.quick ? 2500 : 8000;
  const maxClients = ladder[ladder.length - 1];
  const server = startNode(SERVER, [CROWD_SCENE.scenario, JSON.stringify(CROWD_SCENE.params), String(SNAPSHOT_RATE_HZ), String(maxClients)], { stdin: true });
  try {
    const wsUrl = await nextJson<string>(server, 'wsUrl', 30_000);
    // One player for a few seconds first, so the rain has landed before the first measured step.
    opts.log(`warming ${CROWD_SCENE.label} with one player`);
    await step(server, wsUrl, 1, opts.quick ? 2500 : 5000, 500);
    const steps: Step[] = [];
    for (const n of ladder) {
      opts.log(`${n} clients: ${settleMs} ms settle, ${windowMs} ms window`);
      let s = await step(server, wsUrl, n, settleMs, windowMs);
      // One retry on a miss (the machine is shared); the step counts as passed if the retry passes.
      if (!s.pass && !opts.quick) {
        opts.log(`${n} clients missed (${s.why}); retrying once`);
        const again = await step(server, wsUrl, n, settleMs, windowMs);
        steps.push(s);
        s = again;
      }
      steps.push(s);
      opts.log(`${n} clients: ${s.pass ? 'pass' : `miss (${s.why})`}; tick p99 ${s.tickP99Ms} ms, server CPU ${s.serverCpuShare}, bots CPU ${s.botCpuShare}`);
      if (!s.pass) break;
    }
    const passing = steps.filter((s) => s.pass).map((s) => s.clients);
    const best = passing.length > 0 ? Math.max(...passing) : 0;
    const last = steps[steps.length - 1];
    const botBound = steps.some((s) => !s.pass && s.botCpuShare > 0.9);
    return {
      headline: { clientsPerCore: best },
      detail: {
        scene: CROWD_SCENE,
        snapshotRateHz: SNAPSHOT_RATE_HZ,
        ladder,
        settleMs,
        windowMs,
        steps,
        firstMiss: last.pass ? null : { clients: last.clients, why: last.why },
        botProcessSaturated: botBound,
      },
      rows: [
        { figure: 'clients per core', measure: `largest passing client count (${CROWD_SCENE.label}, ${SNAPSHOT_RATE_HZ} Hz snapshots${opts.quick ? ', coarse ladder' : ''})`, value: best, unit: '', digits: 0, goal: { op: '>=', value: GOAL } },
        ...(last.pass ? [] : [{ figure: 'clients per core', measure: `first miss at ${last.clients}: tick p99 (${last.why})`, value: last.tickP99Ms, unit: 'ms', digits: 1 }]),
      ],
      charts: [
        {
          title: `Clients per core: server tick p99 by client count (${CROWD_SCENE.label}, ${SNAPSHOT_RATE_HZ} Hz snapshots)`,
          unit: 'ms',
          goal: TICK_BUDGET_MS,
          bars: steps.map((s) => ({ label: `${s.clients} clients${s.pass ? '' : ' (miss)'}`, value: s.tickP99Ms, series: s.pass ? ('ours' as const) : ('baseline' as const) })),
        },
      ],
      notes: [
        `Server: startServer in its own process (${CROWD_SCENE.label}, default room, 60 Hz tick, ${SNAPSHOT_RATE_HZ} Hz snapshots, connection caps lifted: the serve command stops at 256 connections); each room tick is timed. Bots: one process of client-library players (decode, ack, interpolate, clock sync, inputs every tick; walk, turn, sprint, jump; no firing).`,
        `A step passes when the window's tick p99 ≤ ${TICK_BUDGET_MS.toFixed(1)} ms, ≤ 1% of snapshots are skipped and no client is dropped${opts.quick ? '' : '; a missed step is retried once'}. Server and bots share this 2-core machine (CPU shares per step in detail.steps).`,
        ...(botBound ? ['The bot process used more than 90% of a core at the first miss: the client side may be the limit there.'] : []),
      ],
    };
  } finally {
    await stopChild(server);
  }
}

/** The clients-per-core figure. */
export const figure: FigureImpl = { run };
