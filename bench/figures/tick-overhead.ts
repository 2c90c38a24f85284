// Tick overhead: for cubes-901 and the 1000-body shape-rain pile, the honest floor (every character's update plus the
// bare Jolt step) against the full server tick over the same ticks (arrived client messages as the real client sends
// them, the room's record, characters, bullets, sensor events, the input log with a state hash every tick, snapshot
// encoding for 1, 16 and 64 clients), in alternating batches; reported as ms over the floor, ratio and cost per client,
// with the GC pause time inside each full tick (perf_hooks 'gc' entries).
import { PerformanceObserver } from 'node:perf_hooks';
import type { ChartBar, FigureImpl, FigureOutput, ReportRow } from '../lib/figure.ts';
import { floorStepBatch, type FloorTick } from '../lib/raw-step.ts';
import { CUBES_SCENE, createSceneSim, PILE_READY_TICK, PILE_SCENE, stepEmptyTo, type Scene } from '../lib/scenes.ts';
import { gcPauseInSpans, type GcPause, type Span } from '../lib/rules.ts';
import { startServerRig, type TickParts } from '../lib/server-rig.ts';
import { linearFit, median, ratio, round, roundSummary, summarize, type Summary } from '../lib/stats.ts';
import { kbps } from '../lib/wire.ts';
import { TICK_RATE_HZ } from '../../shared/tick-rate.ts';

const CLIENT_COUNTS = [1, 16, 64] as const;
/** The goal for what the server adds over the floor at 16 clients (ms). */
const GOAL_OVER_MS = 0.3;
/** A ratio goal only where the floor is large enough for one to hold (the pile); cubes-901's floor is ~0.2 ms. */
const GOAL_RATIO = 1.1;
/** Every tick carries snapshot work (the server's 30 Hz default would leave every other tick without it). */
const SNAPSHOT_RATE_HZ = 60;
/** 50 ms each way: acks come back 100 ms after their snapshot, as on a real network. */
const ONE_WAY_TICKS = 3;

interface ConfigResult {
  scene: string;
  clients: number;
  ticks: number;
  /** The honest floor: each character's update plus the bare Jolt step, over the same ticks as the full tick. */
  floorMs: Summary;
  /** Of the floor: the bare Jolt step, and the characters' updates (medians). */
  floorStepMedianMs: number;
  floorCharactersMedianMs: number;
  fullMs: Summary;
  /** Median full tick − median floor (ms): what the server adds over work no server can skip. */
  overMedianMs: number;
  medianRatio: number | null;
  p99Ratio: number | null;
  /** The old measure, against the bare step alone (characters counted as overhead). */
  bareStepMedianRatio: number | null;
  /** Median ms per tick of each part of the full tick; `other` is the rest (room bookkeeping, log records, GC). */
  partsMedianMs: Record<keyof TickParts | 'other', number>;
  downstreamKbpsPerClient: number;
  /** GC pause ms inside each full tick (pauses that started during it): p99, max and how many ticks had one. */
  gcPauseMsPerTick: { p99: number; max: number; ticksWithGc: number };
}

/** Per scene: the full tick's excess over the floor as a fixed part plus a cost per client (fit over the client counts). */
interface SceneCost {
  scene: string;
  usPerClient: number;
  fixedMs: number;
  r2: number;
}

async function warmStart(scene: Scene, log: (m: string) => void): Promise<Uint8Array | null> {
  if (scene.scenario !== PILE_SCENE.scenario) return null;
  log(`warming ${scene.label} to tick ${PILE_READY_TICK}`);
  const sim = await createSceneSim(scene);
  try {
    stepEmptyTo(sim, PILE_READY_TICK);
    return sim.saveCheckpointBytes();
  } finally {
    sim.destroy();
  }
}

/** Lets perf_hooks hand over the GC entries it has buffered (they arrive on a later turn of the event loop). */
function flushGcEntries(): Promise<void> {
  return new Promise((resolve) => setTimeout(resolve, 20));
}

async function measure(scene: Scene, startBytes: Uint8Array | null, clients: number, quick: boolean, pauses: readonly GcPause[], log: (m: string) => void): Promise<ConfigResult> {
  const warmTicks = quick ? 15 : 40;
  const batches = quick ? 5 : 16;
  const batchTicks = quick ? 8 : 15;
  const rig = await startServerRig({ scenario: scene.scenario, params: scene.params, startBytes, clients, snapshotRateHz: SNAPSHOT_RATE_HZ, oneWayTicks: ONE_WAY_TICKS, hashEveryTicks: 1 });
  try {
    for (let i = 0; i < warmTicks; i++) {
      rig.serverTick();
      await rig.clientTick();
    }
    const before = rig.downstream();
    const floor: FloorTick[] = [];
    const full: number[] = [];
    const parts: TickParts[] = [];
    const spans: Span[] = [];
    log(`${scene.label}, ${clients} client(s): ${batches} × (${batchTicks} floor + ${batchTicks} full ticks)`);
    for (let b = 0; b < batches; b++) {
      // The first tick of each batch follows a checkpoint save (floor) or restore (full): both are dropped.
      floor.push(...floorStepBatch(rig.sim, batchTicks + 1).slice(1));
      for (let i = 0; i <= batchTicks; i++) {
        rig.takeParts();
        const t0 = performance.now();
        rig.serverTick();
        const t1 = performance.now();
        const ms = t1 - t0;
        const p = rig.takeParts();
        if (i > 0) {
          spans.push({ startMs: t0, endMs: t1 });
          full.push(ms);
          parts.push(p);
        }
        await rig.clientTick();
      }
    }
    const after = rig.downstream();
    await flushGcEntries();
    const gcPerTick = gcPauseInSpans(spans, pauses);
    const gc = summarize(gcPerTick);
    const r = summarize(floor.map((t) => t.ms));
    const f = summarize(full);
    const partMedian = (key: keyof TickParts): number => round(median(parts.map((p) => p[key])), 4);
    // simStep contains characters and physicsStep; `other` is what no part accounts for.
    const other = full.map((ms, i) => ms - (parts[i].messagesIn + parts[i].simStep + parts[i].stateHash + parts[i].snapshots + parts[i].events));
    const bare = median(floor.map((t) => t.ms - t.characterMs));
    return {
      scene: scene.label,
      clients,
      ticks: full.length,
      floorMs: roundSummary(r),
      floorStepMedianMs: round(bare, 4),
      floorCharactersMedianMs: round(median(floor.map((t) => t.characterMs)), 4),
      fullMs: roundSummary(f),
      overMedianMs: round(f.median - r.median, 4),
      medianRatio: ratio(f.median, r.median),
      p99Ratio: ratio(f.p99, r.p99),
      bareStepMedianRatio: ratio(f.median, bare),
      partsMedianMs: {
        messagesIn: partMedian('messagesIn'),
        simStep: partMedian('simStep'),
        characters: partMedian('characters'),
        physicsStep: partMedian('physicsStep'),
        stateHash: partMedian('stateHash'),
        snapshots: partMedian('snapshots'),
        events: partMedian('events'),
        other: round(median(other), 4),
      },
      gcPauseMsPerTick: { p99: round(gc.p99, 3), max: round(gc.max, 3), ticksWithGc: gcPerTick.filter((ms) => ms > 0).length },
      downstreamKbpsPerClient: round(kbps(after.bytesPerClient - before.bytesPerClient, (batches * (batchTicks + 1)) / TICK_RATE_HZ), 1),
    };
  } finally {
    await rig.close();
  }
}

/** The excess over the floor against the client count, per scene. */
function sceneCosts(results: readonly ConfigResult[]): SceneCost[] {
  const out: SceneCost[] = [];
  for (const scene of new Set(results.map((r) => r.scene))) {
    const rs = results.filter((r) => r.scene === scene);
    if (new Set(rs.map((r) => r.clients)).size < 2) continue;
    const fit = linearFit(
      rs.map((r) => r.clients),
      rs.map((r) => r.overMedianMs),
    );
    out.push({ scene, usPerClient: round(fit.slope * 1000, 2), fixedMs: round(fit.intercept, 3), r2: round(fit.r2, 3) });
  }
  return out;
}

async function run(opts: { quick: boolean; log(m: string): void }): Promise<FigureOutput> {
  const results: ConfigResult[] = [];
  const pauses: GcPause[] = [];
  const gcObserver = new PerformanceObserver((list) => {
    for (const e of list.getEntries()) pauses.push({ startTime: e.startTime, duration: e.duration });
  });
  gcObserver.observe({ entryTypes: ['gc'] });
  try {
    for (const scene of [CUBES_SCENE, PILE_SCENE] as Scene[]) {
      const startBytes = await warmStart(scene, opts.log);
      for (const clients of CLIENT_COUNTS) results.push(await measure(scene, startBytes, clients, opts.quick, pauses, opts.log));
    }
  } finally {
    gcObserver.disconnect();
  }
  const costs = sceneCosts(results);
  const at16 = results.filter((r) => r.clients === 16);
  const worst = (values: (number | null)[]): number | null => (values.length === 0 || values.some((v) => v === null) ? null : Math.max(...(values as number[])));
  const rows: ReportRow[] = [];
  const bars: ChartBar[] = [];
  const ratioGoal = (scene: string) => (scene === PILE_SCENE.label ? { op: '<=' as const, value: GOAL_RATIO } : undefined);
  for (const scene of new Set(results.map((r) => r.scene))) {
    for (const r of results.filter((x) => x.scene === scene)) {
      const goal = r.clients === 16 ? { op: '<=' as const, value: GOAL_OVER_MS } : undefined;
      const cl = `${r.clients} client${r.clients === 1 ? '' : 's'}`;
      rows.push({ figure: 'tick overhead', measure: `${scene}, ${cl}: full − floor, median (${r.fullMs.median.toFixed(2)} − ${r.floorMs.median.toFixed(2)} ms; ${r.medianRatio?.toFixed(2) ?? 'n/a'}×)`, value: r.overMedianMs, unit: 'ms', digits: 2, goal });
      bars.push({ label: `${scene}, ${r.clients} cl.`, value: r.overMedianMs, series: 'ours' });
    }
    const r16 = at16.find((r) => r.scene === scene);
    if (r16) {
      rows.push({ figure: 'tick overhead', measure: `${scene}, 16 clients: full/floor median`, value: r16.medianRatio, unit: '×', digits: 2, goal: ratioGoal(scene) });
      rows.push({ figure: 'tick overhead', measure: `${scene}, 16 clients: full/floor p99 (${r16.fullMs.p99.toFixed(2)}/${r16.floorMs.p99.toFixed(2)} ms)`, value: r16.p99Ratio, unit: '×', digits: 2, goal: ratioGoal(scene) });
    }
    if (r16) {
      const g = r16.gcPauseMsPerTick;
      rows.push({ figure: 'tick overhead', measure: `${scene}, 16 clients: GC pause inside a full tick, p99 (max ${g.max.toFixed(2)} ms; ${g.ticksWithGc} of ${r16.ticks} ticks had one)`, value: g.p99, unit: 'ms', digits: 2 });
    }
    const c = costs.find((x) => x.scene === scene);
    if (c) {
      rows.push({ figure: 'tick overhead', measure: `${scene}: per client per tick, in-process, no sockets (fit over ${CLIENT_COUNTS.join('/')} clients)`, value: c.usPerClient, unit: 'µs', digits: 1 });
      rows.push({ figure: 'tick overhead', measure: `${scene}: fixed part over the floor (fit at 0 clients, r² ${c.r2})`, value: c.fixedMs, unit: 'ms', digits: 2 });
    }
  }
  const headlineRatio = worst(at16.map((r) => r.medianRatio));
  const headlineP99 = worst(at16.map((r) => r.p99Ratio));
  const headlineOver = worst(at16.map((r) => r.overMedianMs));
  const headlineGc = worst(at16.map((r) => r.gcPauseMsPerTick.p99));
  return {
    headline: {
      tickOverheadRatio16: headlineRatio === null ? null : round(headlineRatio, 3),
      tickOverheadP99Ratio16: headlineP99 === null ? null : round(headlineP99, 3),
      fixedOverheadMs16: headlineOver === null ? null : round(headlineOver, 3),
      tickGcPauseP99Ms16: headlineGc === null ? null : round(headlineGc, 3),
    },
    detail: {
      snapshotRateHz: SNAPSHOT_RATE_HZ,
      oneWayLatencyTicks: ONE_WAY_TICKS,
      hashEveryTicks: 1,
      goalOverMs16: GOAL_OVER_MS,
      goalRatioPile: GOAL_RATIO,
      headlineIs: 'the larger of the two scenes at 16 clients (ratios and ms over the floor)',
      floorIs: 'every present character updated (CharacterController.move) plus the bare PhysicsWorld.stepFixed(), over the same ticks',
      sceneCosts: costs,
      configs: results.map((r) => ({ ...r, medianRatio: r.medianRatio === null ? null : round(r.medianRatio, 3), p99Ratio: r.p99Ratio === null ? null : round(r.p99Ratio, 3), bareStepMedianRatio: r.bareStepMedianRatio === null ? null : round(r.bareStepMedianRatio, 3) })),
    },
    rows,
    charts: [
      { title: 'Tick overhead: full server tick − honest floor (median ms, same ticks)', unit: 'ms over the floor', bars, goal: GOAL_OVER_MS },
      {
        title: 'Where the full tick goes at 16 clients (median ms per part)',
        unit: 'ms',
        bars: at16.flatMap((r) => {
          const p = r.partsMedianMs;
          return [
            { label: `${r.scene}: floor (characters + bare step)`, value: r.floorMs.median, series: 'raw' as const },
            { label: `${r.scene}: characters in the tick`, value: p.characters, series: 'other' as const },
            { label: `${r.scene}: Jolt step in the tick`, value: p.physicsStep, series: 'other' as const },
            { label: `${r.scene}: rest of Simulation.step`, value: Math.max(0, p.simStep - p.physicsStep - p.characters), series: 'ours' as const },
            { label: `${r.scene}: state hash`, value: p.stateHash, series: 'ours' as const },
            { label: `${r.scene}: snapshots (16 clients)`, value: p.snapshots, series: 'ours' as const },
            { label: `${r.scene}: client messages, events, other`, value: p.messagesIn + p.events + Math.max(0, p.other), series: 'ours' as const },
          ];
        }),
      },
    ],
    notes: [
      `Floor: per tick, every present character's update (its last command applied, CharacterController.move: Jolt's ExtendedUpdate) then the bare PhysicsWorld.stepFixed(), from a fast checkpoint, rolled back; full: the same ticks through the real GameServer, Room and ClientSessions (tick-scheduled in-process links, ${ONE_WAY_TICKS} ticks each way), snapshots at ${SNAPSHOT_RATE_HZ} Hz, the room's input log written with a state hash every tick. Batches alternate floor and full; the first tick of each batch (right after a checkpoint save or restore) is dropped on both sides.`,
      'Clients send what the client library sends: one input message per tick from its InputSender (the newest command plus 3 repeats), an ack per snapshot, a ping per second; handling them is inside the full tick (messagesIn). Socket writes are not (the clients-per-core figure covers real sockets).',
      `Headline keys take the larger of the two scenes at 16 clients. fixedOverheadMs16 is the full tick's median minus the floor's at 16 clients (goal ≤ ${GOAL_OVER_MS} ms); the per-client µs and the fixed part come from a line through the 1, 16 and 64-client excesses. A ratio goal (≤ ${GOAL_RATIO}) is set only on ${PILE_SCENE.label}: on cubes-901 the floor is a few tenths of a ms, where per-client work alone exceeds 10% of it.`,
      `cubes-901 starts at tick 0 with player 1 rolling the big cube; ${PILE_SCENE.label} starts from tick ${PILE_READY_TICK} (every drop landed). Clients are scripted bots (walk, jump, fire).`,
      "tickGcPauseP99Ms16: GC pause ms inside one full tick (perf_hooks 'gc' entries that started during it), p99 over the measured full ticks, the larger of the two scenes at 16 clients; in-process, so it counts the room's garbage and the in-process clients' (clients-per-core's gcPauseP99Ms is the server process alone, per 1/60 s). detail.configs[].gcPauseMsPerTick has every configuration.",
      'detail.configs[].partsMedianMs splits the full tick: messagesIn (inputs, acks, pings), simStep (of which characters and physicsStep), stateHash, snapshots (quantize, delta-encode, frame), events, other; bareStepMedianRatio is the old measure (full over the bare step, characters counted as overhead).',
    ],
  };
}

/** The tick-overhead figure. */
export const figure: FigureImpl = { run };
