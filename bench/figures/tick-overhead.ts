// Tick overhead: for cubes-901 and the 1000-body shape-rain pile, the raw PhysicsWorld step loop against the full
// server tick over the same ticks (arrived inputs and acks, the room's record, characters, bullets, sensor events,
// the input log with a state hash every tick, snapshot encoding for 1, 16 and 64 clients), in alternating batches.
import { TICK_RATE_HZ } from '../../shared/tick-rate.ts';
import type { ChartBar, FigureImpl, FigureOutput, ReportRow } from '../lib/figure.ts';
import { rawStepBatch } from '../lib/raw-step.ts';
import { CUBES_SCENE, createSceneSim, PILE_READY_TICK, PILE_SCENE, stepEmptyTo, type Scene } from '../lib/scenes.ts';
import { startServerRig, type TickParts } from '../lib/server-rig.ts';
import { median, ratio, round, roundSummary, summarize, type Summary } from '../lib/stats.ts';
import { kbps } from '../lib/wire.ts';

const CLIENT_COUNTS = [1, 16, 64] as const;
const GOAL = 1.1;
/** Every tick carries snapshot work (the server's 30 Hz default would leave every other tick without it). */
const SNAPSHOT_RATE_HZ = 60;
/** 50 ms each way: acks come back 100 ms after their snapshot, as on a real network. */
const ONE_WAY_TICKS = 3;

interface ConfigResult {
  scene: string;
  clients: number;
  ticks: number;
  rawMs: Summary;
  fullMs: Summary;
  medianRatio: number | null;
  p99Ratio: number | null;
  /** Median ms per tick of each part of the full tick; `other` is the rest (room bookkeeping, log records, GC). */
  partsMedianMs: Record<keyof TickParts | 'other', number>;
  downstreamKbpsPerClient: number;
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

async function measure(scene: Scene, startBytes: Uint8Array | null, clients: number, quick: boolean, log: (m: string) => void): Promise<ConfigResult> {
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
    const raw: number[] = [];
    const full: number[] = [];
    const parts: TickParts[] = [];
    log(`${scene.label}, ${clients} client(s): ${batches} × (${batchTicks} raw + ${batchTicks} full ticks)`);
    for (let b = 0; b < batches; b++) {
      // The first tick of each batch follows a checkpoint save (raw) or restore (full): both are dropped.
      raw.push(...rawStepBatch(rig.sim, batchTicks + 1).slice(1));
      for (let i = 0; i <= batchTicks; i++) {
        rig.takeParts();
        const t0 = performance.now();
        rig.serverTick();
        const ms = performance.now() - t0;
        const p = rig.takeParts();
        if (i > 0) {
          full.push(ms);
          parts.push(p);
        }
        await rig.clientTick();
      }
    }
    const after = rig.downstream();
    const r = summarize(raw);
    const f = summarize(full);
    const n = full.length;
    const partMedian = (key: keyof TickParts): number => round(median(parts.map((p) => p[key])), 4);
    // simStep contains physicsStep; `other` is what no part accounts for.
    const other = full.map((ms, i) => ms - (parts[i].messagesIn + parts[i].simStep + parts[i].stateHash + parts[i].snapshots + parts[i].events));
    return {
      scene: scene.label,
      clients,
      ticks: n,
      rawMs: roundSummary(r),
      fullMs: roundSummary(f),
      medianRatio: ratio(f.median, r.median),
      p99Ratio: ratio(f.p99, r.p99),
      partsMedianMs: {
        messagesIn: partMedian('messagesIn'),
        simStep: partMedian('simStep'),
        physicsStep: partMedian('physicsStep'),
        stateHash: partMedian('stateHash'),
        snapshots: partMedian('snapshots'),
        events: partMedian('events'),
        other: round(median(other), 4),
      },
      downstreamKbpsPerClient: round(kbps(after.bytesPerClient - before.bytesPerClient, (batches * (batchTicks + 1)) / TICK_RATE_HZ), 1),
    };
  } finally {
    await rig.close();
  }
}

async function run(opts: { quick: boolean; log(m: string): void }): Promise<FigureOutput> {
  const results: ConfigResult[] = [];
  for (const scene of [CUBES_SCENE, PILE_SCENE] as Scene[]) {
    const startBytes = await warmStart(scene, opts.log);
    for (const clients of CLIENT_COUNTS) results.push(await measure(scene, startBytes, clients, opts.quick, opts.log));
  }
  const at16 = results.filter((r) => r.clients === 16);
  const worst = (values: (number | null)[]): number | null => (values.some((v) => v === null) ? null : Math.max(...(values as number[])));
  const rows: ReportRow[] = [];
  const bars: ChartBar[] = [];
  for (const r of results) {
    const goal = r.clients === 16 ? { op: '<=' as const, value: GOAL } : undefined;
    rows.push({ figure: 'tick overhead', measure: `${r.scene}, ${r.clients} client${r.clients === 1 ? '' : 's'}: full/raw median (${r.fullMs.median.toFixed(2)}/${r.rawMs.median.toFixed(2)} ms)`, value: r.medianRatio, unit: '×', digits: 2, goal });
    if (r.clients === 16) rows.push({ figure: 'tick overhead', measure: `${r.scene}, 16 clients: full/raw p99 (${r.fullMs.p99.toFixed(2)}/${r.rawMs.p99.toFixed(2)} ms)`, value: r.p99Ratio, unit: '×', digits: 2, goal });
    bars.push({ label: `${r.scene}, ${r.clients} cl. (median)`, value: r.medianRatio, series: 'ours' });
  }
  for (const r of at16) bars.push({ label: `${r.scene}, 16 cl. (p99)`, value: r.p99Ratio, series: 'other' });
  const headlineRatio = worst(at16.map((r) => r.medianRatio));
  const headlineP99 = worst(at16.map((r) => r.p99Ratio));
  return {
    headline: {
      tickOverheadRatio16: headlineRatio === null ? null : round(headlineRatio, 3),
      tickOverheadP99Ratio16: headlineP99 === null ? null : round(headlineP99, 3),
    },
    detail: {
      snapshotRateHz: SNAPSHOT_RATE_HZ,
      oneWayLatencyTicks: ONE_WAY_TICKS,
      hashEveryTicks: 1,
      goal: GOAL,
      headlineIs: 'the larger of the two scenes at 16 clients',
      configs: results.map((r) => ({ ...r, medianRatio: r.medianRatio === null ? null : round(r.medianRatio, 3), p99Ratio: r.p99Ratio === null ? null : round(r.p99Ratio, 3) })),
    },
    rows,
    charts: [
      { title: 'Tick overhead: full server tick / raw Jolt step, same ticks', unit: '× raw step (log)', log: true, bars, goal: GOAL },
      {
        title: 'Where the full tick goes at 16 clients (median ms per part)',
        unit: 'ms',
        bars: at16.flatMap((r) => {
          const p = r.partsMedianMs;
          return [
            { label: `${r.scene}: raw Jolt step`, value: r.rawMs.median, series: 'raw' as const },
            { label: `${r.scene}: Jolt step in the tick`, value: p.physicsStep, series: 'other' as const },
            { label: `${r.scene}: rest of Simulation.step`, value: Math.max(0, p.simStep - p.physicsStep), series: 'ours' as const },
            { label: `${r.scene}: state hash`, value: p.stateHash, series: 'ours' as const },
            { label: `${r.scene}: snapshots (16 clients)`, value: p.snapshots, series: 'ours' as const },
            { label: `${r.scene}: inputs, acks, events, other`, value: p.messagesIn + p.events + Math.max(0, p.other), series: 'ours' as const },
          ];
        }),
      },
    ],
    notes: [
      `Raw: bare PhysicsWorld.stepFixed() from a fast checkpoint, rolled back; full: the same ticks through the real GameServer, Room and ClientSessions (tick-scheduled in-process links, ${ONE_WAY_TICKS} ticks each way), snapshots at ${SNAPSHOT_RATE_HZ} Hz, the room's input log written with a state hash every tick. Batches alternate raw and full; the first tick of each batch (right after a checkpoint save or restore) is dropped on both sides.`,
      'Headline keys take the larger of the two scenes at 16 clients. Socket writes are not in the full tick here (the clients-per-core figure covers real sockets).',
      `cubes-901 starts at tick 0 with player 1 rolling the big cube; ${PILE_SCENE.label} starts from tick ${PILE_READY_TICK} (every drop landed). Clients are scripted bots (walk, jump, fire).`,
      'detail.configs[].partsMedianMs splits the full tick: messagesIn (inputs, acks), simStep (of which physicsStep is Jolt), stateHash, snapshots (quantize, delta-encode, frame), events, other.',
    ],
  };
}

/** The tick-overhead figure. */
export const figure: FigureImpl = { run };
