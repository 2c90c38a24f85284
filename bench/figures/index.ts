// The figure registry: every benchmark figure in table order, with its headline keys in latest.json, its detail key,
// its time limit and the module that runs it (each figure runs in its own process, see bench/lib/figure-process.ts).
import type { FigureSpec } from '../lib/figure.ts';

const min = (m: number): number => m * 60_000;

/** Every figure, in the order of the table. */
export const FIGURES: readonly FigureSpec[] = Object.freeze([
  {
    name: 'tick-overhead',
    title: 'tick overhead',
    detailKey: 'tickOverhead',
    headlineKeys: ['tickOverheadRatio16', 'tickOverheadP99Ratio16', 'fixedOverheadMs16'],
    timeLimitMs: (quick: boolean) => (quick ? min(3) : min(5)),
    module: 'figures/tick-overhead.ts',
  },
  {
    name: 'bandwidth',
    title: 'bandwidth',
    detailKey: 'bandwidth',
    headlineKeys: ['kbpsJoin60Hz', 'kbpsSteady60Hz', 'kbpsPushed60Hz', 'kbpsAtRest60Hz', 'kbpsPerClient60Hz', 'kbpsPerClient20Hz', 'naiveKbps60Hz', 'colyseusKbps60Hz'],
    timeLimitMs: (quick: boolean) => (quick ? min(3) : min(5)),
    module: 'figures/bandwidth.ts',
  },
  {
    name: 'clients-per-core',
    title: 'clients per core',
    detailKey: 'clientsPerCoreDetail',
    headlineKeys: ['clientsPerCoreStock', 'clientsPerCoreCrowd', 'usPerClientTick', 'gcPauseP99Ms'],
    timeLimitMs: (quick: boolean) => (quick ? min(3) : min(8)),
    module: 'figures/clients-per-core.ts',
  },
  {
    name: 'rooms-per-core',
    title: 'rooms per core',
    detailKey: 'roomsPerCoreDetail',
    headlineKeys: ['roomsPerCore'],
    timeLimitMs: (quick: boolean) => (quick ? min(3) : min(6)),
    module: 'figures/rooms-per-core.ts',
  },
  {
    name: 'input-latency',
    title: 'input latency',
    detailKey: 'inputLatency',
    headlineKeys: ['inputLatencyTicks'],
    timeLimitMs: (quick: boolean) => (quick ? min(3) : min(3)),
    module: 'figures/input-latency.ts',
  },
  {
    name: 'replay',
    title: 'replay',
    detailKey: 'replay',
    headlineKeys: ['replayRatio'],
    timeLimitMs: (quick: boolean) => (quick ? min(3) : min(5)),
    module: 'figures/replay.ts',
  },
  {
    name: 'determinism-cost',
    title: 'determinism cost',
    detailKey: 'determinismCost',
    headlineKeys: ['hashMsPerTick1000', 'checkpointSaveMs1000', 'checkpointRestoreMs1000'],
    timeLimitMs: (quick: boolean) => (quick ? min(3) : min(3)),
    module: 'figures/determinism-cost.ts',
  },
  {
    name: 'engine-peer',
    title: 'engine peer',
    detailKey: 'enginePeer',
    headlineKeys: [],
    peersOnly: true,
    timeLimitMs: (quick: boolean) => (quick ? min(3) : min(3)),
    module: 'figures/engine-peer.ts',
  },
  {
    name: 'startup',
    title: 'start-up',
    detailKey: 'startup',
    headlineKeys: ['startupMs'],
    timeLimitMs: (quick: boolean) => (quick ? min(3) : min(3)),
    module: 'figures/startup.ts',
  },
  {
    name: 'fleet-redirect',
    title: 'fleet redirect',
    detailKey: 'fleetRedirect',
    headlineKeys: ['redirectWelcomeMs'],
    timeLimitMs: (quick: boolean) => (quick ? min(2) : min(3)),
    module: 'figures/fleet-redirect.ts',
  },
]);

/** Every figure name. */
export const FIGURE_NAMES: readonly string[] = FIGURES.map((f) => f.name);

/** The headline keys of latest.json, in the order. */
export const HEADLINE_KEYS: readonly string[] = [
  'tickOverheadRatio16',
  'tickOverheadP99Ratio16',
  'fixedOverheadMs16',
  'kbpsJoin60Hz',
  'kbpsSteady60Hz',
  'kbpsPushed60Hz',
  'kbpsAtRest60Hz',
  'kbpsPerClient60Hz',
  'kbpsPerClient20Hz',
  'naiveKbps60Hz',
  'colyseusKbps60Hz',
  'clientsPerCoreStock',
  'clientsPerCoreCrowd',
  'usPerClientTick',
  'gcPauseP99Ms',
  'roomsPerCore',
  'inputLatencyTicks',
  'replayRatio',
  'hashMsPerTick1000',
  'checkpointSaveMs1000',
  'checkpointRestoreMs1000',
  'startupMs',
  'redirectWelcomeMs',
];
