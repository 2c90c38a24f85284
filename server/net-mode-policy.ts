// Which net mode a room gets: predict when the client's cost of rolling back fits a frame, snapshot otherwise. The
// cost is an estimate per built-in scenario (its measured tick time at default parameters, scaled by the parameter
// that sets how many bodies move) or the scenario's own `tickCostMs`, so the choice is the same on every server and
// known before anyone joins. Scenarios using the game API predict like any other (records carry game input and
// messages).
import { NetMode } from '../shared/protocol/predict-messages.ts';

/** What a room is asked for: a mode, or 'auto' (predict when affordable). */
export type NetModeRequest = NetMode | 'auto';

/** Whether a value is a net-mode request. */
export function isNetModeRequest(value: unknown): value is NetModeRequest {
  return value === 'auto' || value === NetMode.Snapshot || value === NetMode.Predict;
}

/** A client's frame at 60 Hz (ms): re-simulating the rollback must fit in it. */
export const FRAME_BUDGET_MS = 1000 / 60;
/** Rollback depth a client at 100 ms round trip re-simulates each frame (the round trip in ticks). */
export const EXPECTED_ROLLBACK_TICKS = 6;

interface CostModel {
  /** Tick time at default parameters with 4 bots (ms, one core of a quiet desktop; bench/ measures it). */
  msPerTick: number;
  /** How many times the default body load the parameters ask for (1 at defaults). */
  load?: (p: Readonly<Record<string, number>>) => number;
}

const COST: Readonly<Record<string, CostModel>> = {
  'character-course': { msPerTick: 0.3 },
  'convex-hulls': { msPerTick: 2.2, load: (p) => (p.count ?? 150) / 150 },
  'crowd-arena': { msPerTick: 0.3, load: (p) => (p.props ?? 256) / 256 },
  'cubes-901': { msPerTick: 0.12, load: (p) => ((p.side ?? 30) * (p.side ?? 30)) / 900 },
  'height-field': { msPerTick: 2.2, load: (p) => (p.bodyCount ?? 80) / 80 },
  'mesh-terrain': { msPerTick: 1.6, load: (p) => (p.bodyCount ?? 80) / 80 },
  'pendulum-chain': { msPerTick: 2.4, load: (p) => ((p.chains ?? 5) * ((p.links ?? 12) + (p.pinsPerChain ?? 5))) / 85 },
  'shape-rain': { msPerTick: 2.3, load: (p) => (p.count ?? 300) / 300 },
  'terrain-balls': { msPerTick: 0.45 },
};

/** The effective mode of a room and, when it is not the one asked for, why. */
export interface NetModeDecision {
  mode: NetMode;
  /** Ticks of rollback a 16.7 ms frame affords by the estimate (null: no estimate for this scenario). */
  affordableRollbackTicks: number | null;
  /** Why the room serves snapshots although predict was asked for (or allowed by 'auto'); null otherwise. */
  note: string | null;
}

/**
 * Decides a room's net mode from the request, the scenario and its resolved parameters. `ownTickCostMs`: the
 * scenario's own estimate at default parameters (ScenarioDefinition.tickCostMs), used when it is not a built-in.
 */
export function decideNetMode(request: NetModeRequest, scenario: string, params: Readonly<Record<string, number>>, ownTickCostMs?: number): NetModeDecision {
  const builtIn = Object.hasOwn(COST, scenario) ? COST[scenario] : undefined;
  const model = builtIn ?? (ownTickCostMs !== undefined && ownTickCostMs > 0 ? { msPerTick: ownTickCostMs } : undefined);
  const estimateMs = model ? model.msPerTick * Math.max(model.load?.(params) ?? 1, 0.01) : null;
  const affordable = estimateMs === null ? null : Math.floor(FRAME_BUDGET_MS / estimateMs);
  if (request === NetMode.Snapshot) return { mode: NetMode.Snapshot, affordableRollbackTicks: affordable, note: null };
  if (affordable === null) {
    // No estimate (a scenario outside the built-in set): predict only when asked for by name.
    if (request === NetMode.Predict) return { mode: NetMode.Predict, affordableRollbackTicks: null, note: null };
    return { mode: NetMode.Snapshot, affordableRollbackTicks: null, note: `no cost estimate for scenario ${scenario} (its definition gives no tickCostMs): snapshot mode` };
  }
  if (affordable < EXPECTED_ROLLBACK_TICKS) {
    return {
      mode: NetMode.Snapshot,
      affordableRollbackTicks: affordable,
      note: `snapshot mode: a tick costs about ${estimateMs!.toFixed(1)} ms, so a frame affords ${affordable} ticks of rollback, fewer than the ${EXPECTED_ROLLBACK_TICKS} a 100 ms round trip needs`,
    };
  }
  return { mode: NetMode.Predict, affordableRollbackTicks: affordable, note: null };
}
