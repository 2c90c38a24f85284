// Clients per core: the server process pinned to one CPU (stock shape-rain 300, 60 Hz tick, 30 Hz snapshots) and a
// light bot swarm pinned to the other, shown first to load the server like client-library players. N climbs a ladder,
// then bisects after the first miss; a count passes at 60 ticks/s with tick p99 < 16.7 ms. The server's own CPU time
// per tick against N gives the cost per client; the crowd scene runs the same ladder once it exists.
import type { ChartBar, FigureImpl, FigureOutput, ReportRow } from '../lib/figure.ts';
import { clientCost, judgeClientWindow, judgeSwarmProof, ladderResult, nextLadderCount, TICK_BUDGET_MS, type ClientCost, type SwarmLoad } from '../lib/rules.ts';
import { CROWD_SCENE, sceneAvailable, STOCK_SCENE, type Scene } from '../lib/scenes.ts';
import { measureWindow, startBenchServer, stopBenchServer, type BenchServer, type SwarmKind } from '../lib/server-bench.ts';
import { median, round } from '../lib/stats.ts';
import { getScenario } from '../../scenarios/index.ts';
import { DEFAULT_MAX_PLAYERS } from '../../shared/sim/players.ts';

const GOAL_STOCK = 256;
const GOAL_CROWD = 512;
const SNAPSHOT_RATE_HZ = 30;
/** The bot process is taken to be the limit when it used this share of its CPU in a missed window. */
const BOT_SATURATED_SHARE = 0.9;
/** The fixed client count whose window gives the headline GC pause per tick. */
const GC_CLIENTS = 64;

interface Step {
  clients: number;
  swarm: SwarmKind;
  pass: boolean;
  why: string;
  ticks: number;
  ticksPerSecond: number;
  tickP50Ms: number | null;
  tickP99Ms: number | null;
  tickMaxMs: number | null;
  /** The tick's own CPU time on the server's main thread (unaffected by other processes taking the core). */
  tickCpuP99Ms: number | null;
  /** Server process CPU time per room tick (ms): every thread, message handling and socket writes included. */
  cpuMsPerTick: number;
  serverCpuShare: number;
  botCpuShare: number;
  botSaturated: boolean;
  gcPerTickP99Ms: number;
  gcMaxMs: number;
  snapshotsSkippedShare: number;
  slowdownTicks: number;
  messagesPerClientPerSecond: number;
  bytesUpPerClientPerSecond: number;
  kbpsPerClient: number;
  bodies: number;
}

interface Timing {
  settleMs: number;
  windowMs: number;
}

async function step(server: BenchServer, kind: SwarmKind, clients: number, t: Timing): Promise<Step> {
  const { server: s, bots } = await measureWindow(server, kind, clients, t.settleMs, t.windowMs);
  const room = s.rooms.find((r) => r.id === 'default');
  const ticks = room?.ticks ?? 0;
  const verdict = judgeClientWindow({ seconds: s.seconds, ticks, tickP99Ms: room?.tickWallMs?.p99 ?? null, snapshotsSent: s.snapshotsSent, snapshotsSkipped: s.snapshotsSkipped, droppedClients: bots.closedClients });
  const perClientSecond = (v: number): number => round(v / clients / s.seconds, 1);
  return {
    clients,
    swarm: kind,
    pass: verdict.pass,
    why: verdict.reasons.join('; '),
    ticks,
    ticksPerSecond: round(ticks / s.seconds, 1),
    tickP50Ms: room?.tickWallMs?.p50 ?? null,
    tickP99Ms: room?.tickWallMs?.p99 ?? null,
    tickMaxMs: room?.tickWallMs?.max ?? null,
    tickCpuP99Ms: room?.tickCpuMs?.p99 ?? null,
    cpuMsPerTick: round(ticks > 0 ? s.cpuMs / ticks : NaN, 4),
    serverCpuShare: round(s.cpuShare, 3),
    botCpuShare: round(bots.cpuShare, 3),
    botSaturated: bots.cpuShare >= BOT_SATURATED_SHARE,
    gcPerTickP99Ms: s.gc.perTickP99Ms,
    gcMaxMs: s.gc.maxMs,
    snapshotsSkippedShare: round(s.snapshotsSent + s.snapshotsSkipped > 0 ? s.snapshotsSkipped / (s.snapshotsSent + s.snapshotsSkipped) : 0, 4),
    slowdownTicks: s.ticksSkipped,
    messagesPerClientPerSecond: perClientSecond(s.messagesReceived),
    bytesUpPerClientPerSecond: perClientSecond(s.bytesReceived),
    kbpsPerClient: round(bots.kbpsPerClient, 1),
    bodies: room?.bodies ?? 0,
  };
}

/** Real and light swarms of the same size in alternating windows: does the light one cost the server the same? */
async function proveSwarm(server: BenchServer, clients: number, rounds: number, t: Timing, log: (m: string) => void): Promise<{ steps: Step[]; verdict: ReturnType<typeof judgeSwarmProof> }> {
  const steps: Step[] = [];
  // Past the join burst (full snapshots to decode) before the client-library players are measured.
  const timing = { settleMs: Math.max(2000, t.settleMs), windowMs: t.windowMs };
  for (let i = 0; i < rounds; i++) {
    const order: SwarmKind[] = i % 2 === 0 ? ['real', 'light'] : ['light', 'real'];
    for (const kind of order) {
      log(`swarm check: ${clients} ${kind === 'real' ? 'client-library players' : 'light bots'}`);
      steps.push(await step(server, kind, clients, timing));
    }
  }
  const load = (kind: SwarmKind): SwarmLoad => {
    const of = steps.filter((s) => s.swarm === kind);
    return { cpuMsPerTick: median(of.map((s) => s.cpuMsPerTick)), messagesPerClientPerSecond: median(of.map((s) => s.messagesPerClientPerSecond)), bytesPerClientPerSecond: median(of.map((s) => s.bytesUpPerClientPerSecond)) };
  };
  return { steps, verdict: judgeSwarmProof(load('real'), load('light')) };
}

interface LadderOutcome {
  scene: Scene;
  best: number;
  steps: Step[];
  cost: ClientCost | null;
  firstMiss: Step | null;
}

async function ladder(server: BenchServer, scene: Scene, rungs: readonly number[], resolution: number, retry: boolean, t: Timing, log: (m: string) => void): Promise<LadderOutcome> {
  const results = new Map<number, boolean>();
  const steps: Step[] = [];
  for (let n = nextLadderCount(rungs, results, resolution); n !== null; n = nextLadderCount(rungs, results, resolution)) {
    log(`${scene.label}, ${n} light bots: ${t.settleMs} ms settle, ${t.windowMs} ms window`);
    let s = await step(server, 'light', n, t);
    if (!s.pass && retry && !s.botSaturated) {
      log(`${n} clients missed (${s.why}); retrying once`);
      steps.push(s);
      s = await step(server, 'light', n, t);
    }
    steps.push(s);
    results.set(n, s.pass);
    log(`${n} clients: ${s.pass ? 'pass' : `miss (${s.why})`}; tick p99 ${s.tickP99Ms} ms, ${s.ticksPerSecond} ticks/s, server CPU ${s.serverCpuShare}, bots CPU ${s.botCpuShare}`);
    if (!s.pass && s.botSaturated) break; // the bots, not the server, are the limit: stop here
  }
  const best = ladderResult(results);
  const passing = steps.filter((s) => s.pass && s.ticks > 0);
  // The first count whose final verdict (after any retry) was a miss, and its last window.
  const missed = [...results].filter(([, pass]) => !pass).map(([n]) => n);
  const firstMissAt = missed.length > 0 ? Math.min(...missed) : null;
  return {
    scene,
    best,
    steps,
    cost: clientCost(passing.map((s) => ({ clients: s.clients, cpuMsPerTick: s.cpuMsPerTick }))),
    firstMiss: firstMissAt === null ? null : (steps.filter((s) => s.clients === firstMissAt).at(-1) ?? null),
  };
}

async function runScene(scene: Scene, rungs: readonly number[], resolution: number, quick: boolean, t: Timing, log: (m: string) => void, proofClients: number | null) {
  const server = await startBenchServer(scene, SNAPSHOT_RATE_HZ, Math.max(...rungs));
  try {
    // One player for a few seconds first, so the rain has landed before the first measured window.
    log(`warming ${scene.label} with one light bot`);
    await measureWindow(server, 'light', 1, quick ? 2500 : 5000, 500);
    const proof = proofClients === null ? null : await proveSwarm(server, proofClients, quick ? 1 : 2, t, log);
    return { pinning: server.pinning, proof, outcome: await ladder(server, scene, rungs, resolution, !quick, t, log) };
  } finally {
    await stopBenchServer(server);
  }
}

function ladderRows(o: LadderOutcome, goal: number, quick: boolean): ReportRow[] {
  const cap = getScenario(o.scene.scenario).players?.maxPlayers ?? DEFAULT_MAX_PLAYERS;
  const rows: ReportRow[] = [{ figure: 'clients per core', measure: `largest passing client count (${o.scene.label}, ${SNAPSHOT_RATE_HZ} Hz snapshots${quick ? ', coarse' : ''}; the scene declares a cap of ${cap} players, lifted here)`, value: o.best, unit: '', digits: 0, goal: { op: '>=', value: goal } }];
  if (o.cost) {
    rows.push({ figure: 'clients per core', measure: `${o.scene.label}: server CPU per client per tick (fit over ${o.cost.points} passing counts, r² ${round(o.cost.r2, 3)})`, value: o.cost.usPerClientTick, unit: 'µs', digits: 1 });
    rows.push({ figure: 'clients per core', measure: `${o.scene.label}: server CPU per tick at 0 clients (fit)`, value: o.cost.fixedMsPerTick, unit: 'ms', digits: 2 });
  }
  if (o.firstMiss) rows.push({ figure: 'clients per core', measure: `${o.scene.label}: first miss at ${o.firstMiss.clients}: tick p99 (${o.firstMiss.why})`, value: o.firstMiss.tickP99Ms, unit: 'ms', digits: 1 });
  return rows;
}

async function run(opts: { quick: boolean; log(m: string): void }): Promise<FigureOutput> {
  const quick = opts.quick;
  const t: Timing = quick ? { settleMs: 1000, windowMs: 2500 } : { settleMs: 3000, windowMs: 8000 };
  const stockRungs = quick ? [16, 32, 64, 128, 256] : [16, 32, 64, 96, 128, 160, 192, 256, 320, 384, 512];
  const stock = await runScene(STOCK_SCENE, stockRungs, quick ? 64 : 16, quick, t, opts.log, quick ? 32 : 64);
  const crowdAvailable = sceneAvailable(CROWD_SCENE);
  const crowd = crowdAvailable ? await runScene(CROWD_SCENE, quick ? [64, 256, 512, 1024] : [64, 128, 256, 384, 512, 640, 768, 1024], quick ? 128 : 32, quick, t, opts.log, null) : null;
  const s = stock.outcome;
  const gcStep = s.steps.filter((x) => x.clients === GC_CLIENTS).at(-1); // the retry, when there was one
  const proof = stock.proof!;
  const pinned = stock.pinning;
  const botBound = s.firstMiss?.botSaturated === true;
  const bars: ChartBar[] = s.steps.map((x) => ({ label: `${x.clients} clients${x.pass ? '' : ' (miss)'}`, value: x.tickP99Ms, series: x.pass ? ('ours' as const) : ('baseline' as const) }));
  const rows: ReportRow[] = [...ladderRows(s, GOAL_STOCK, quick)];
  if (crowd) rows.push(...ladderRows(crowd.outcome, GOAL_CROWD, quick));
  else rows.push({ figure: 'clients per core', measure: `largest passing client count (${CROWD_SCENE.label}: no such scenario yet)`, value: null, unit: '', digits: 0, goal: { op: '>=', value: GOAL_CROWD } });
  rows.push({ figure: 'clients per core', measure: `light bots / client-library players, server CPU per tick at ${proof.steps[0].clients} clients (${proof.verdict.pass ? 'within' : 'OUTSIDE'} ±10%)`, value: proof.verdict.ratios.cpuMsPerTick, unit: '×', digits: 3 });
  rows.push({ figure: 'clients per core', measure: `GC pause per tick, p99 (server, ${STOCK_SCENE.label}, ${GC_CLIENTS} clients)`, value: gcStep?.gcPerTickP99Ms ?? null, unit: 'ms', digits: 2 });
  return {
    headline: {
      clientsPerCoreStock: s.best,
      clientsPerCoreCrowd: crowd ? crowd.outcome.best : null,
      usPerClientTick: s.cost ? round(s.cost.usPerClientTick, 2) : null,
      gcPauseP99Ms: gcStep ? gcStep.gcPerTickP99Ms : null,
    },
    detail: {
      scene: STOCK_SCENE,
      snapshotRateHz: SNAPSHOT_RATE_HZ,
      pinning: pinned,
      ...t,
      stock: { ladder: stockRungs, best: s.best, cost: s.cost, firstMiss: s.firstMiss ? { clients: s.firstMiss.clients, why: s.firstMiss.why, botSaturated: s.firstMiss.botSaturated } : null, steps: s.steps },
      crowd: crowd ? { scene: CROWD_SCENE, best: crowd.outcome.best, cost: crowd.outcome.cost, steps: crowd.outcome.steps } : { scene: CROWD_SCENE, measured: false, why: `no scenario "${CROWD_SCENE.scenario}" is registered yet` },
      swarmProof: { clients: proof.steps[0].clients, pass: proof.verdict.pass, reasons: proof.verdict.reasons, ratios: Object.fromEntries(Object.entries(proof.verdict.ratios).map(([k, v]) => [k, round(v, 3)])), steps: proof.steps },
      gcStepClients: GC_CLIENTS,
    },
    rows,
    charts: [{ title: `Clients per core: server tick p99 by client count (${STOCK_SCENE.label}, ${SNAPSHOT_RATE_HZ} Hz snapshots)`, unit: 'ms', goal: TICK_BUDGET_MS, bars }],
    notes: [
      `Server: procs/bench-server.ts, startServer in its own process (${STOCK_SCENE.label}, default room, 60 Hz tick, ${SNAPSHOT_RATE_HZ} Hz snapshots, connection caps lifted: the serve command stops at 256 connections)${pinned ? `, pinned to CPU ${pinned.server} with taskset; the bots pinned to CPU ${pinned.bots}` : ', not pinned (no taskset or a single CPU here)'}. Every room tick is timed (wall and main-thread CPU); the server's own CPU time (process.cpuUsage: every thread, message handling and socket writes included) per room tick gives detail.*.steps[].cpuMsPerTick.`,
      `Bots: procs/light-swarm.ts sends what the client library sends (its InputSender, InputLead and ClockSync on the library's half-tick pump: one input message per tick carrying 4 commands, an ack per snapshot, pings) but reads only each snapshot's header. Check: ${proof.steps[0].clients} light bots against ${proof.steps[0].clients} client-library players (procs/bot-swarm.ts) in alternating windows; light/real server CPU per tick ${round(proof.verdict.ratios.cpuMsPerTick, 3)}, messages ${round(proof.verdict.ratios.messagesPerClientPerSecond, 3)}, bytes ${round(proof.verdict.ratios.bytesPerClientPerSecond, 3)} (${proof.verdict.pass ? 'all within ±10%' : `NOT within ±10%: ${proof.verdict.reasons.join('; ')}`}).`,
      `A count passes when the default room ran ≥ 99% of 60 ticks/s in the window, its tick p99 < ${TICK_BUDGET_MS.toFixed(1)} ms (wall time: another process taking the core shows up here), ≤ 1% of snapshots were skipped and no client was dropped${quick ? '' : '; a miss is retried once'}. After the first miss the search halves the interval down to ${quick ? 64 : 16} clients.`,
      `usPerClientTick: least-squares line through (clients, server CPU ms per tick) of the passing windows. gcPauseP99Ms: GC pause time per 1/60 s of the ${GC_CLIENTS}-client window (perf_hooks 'gc' entries), p99.`,
      ...(crowd ? [] : [`clientsPerCoreCrowd: not measured, no scenario "${CROWD_SCENE.scenario}" is registered yet (bench/lib/scenes.ts names it).`]),
      ...(botBound ? ['The bot process used ≥ 90% of its CPU at the first miss: the bots may be the limit there, not the server.'] : []),
    ],
  };
}

/** The clients-per-core figure. */
export const figure: FigureImpl = { run };
