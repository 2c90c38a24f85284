// Golden runs: a scenario's scripted reference run (its golden tick count, its number of bots, a fixed seed) and the
// stored result `scenarios/<name>.golden.json`. Only `taos-physics goldens --write` (npm run goldens -- --write) ever rewrites those files.
import type { PhysicsWorldOptions } from '../physics/index.ts';
import { BotScript } from './bots.ts';
import type { ScenarioDefinition } from './scenario.ts';
import { Simulation } from './simulation.ts';

/** Seed of every golden run (the simulation's and the bots'). */
export const GOLDEN_SEED = 20240601;
/** Ticks between two golden bot joins. */
export const GOLDEN_JOIN_SPACING_TICKS = 15;
/** A golden run records its hash this often, so a changed run shows where it first departs. */
export const GOLDEN_HASH_EVERY_TICKS = 60;

/** The stored golden record of one scenario. */
export interface GoldenFile {
  scenario: string;
  ticks: number;
  bots: number;
  seed: number;
  /** State hash after `ticks` ticks. */
  hash: string;
  /** The jolt-physics version that produced the hash. */
  joltVersion: string;
}

/** The outcome of one golden run. */
export interface GoldenResult {
  scenario: string;
  ticks: number;
  bots: number;
  seed: number;
  hash: string;
  /** The hash every GOLDEN_HASH_EVERY_TICKS ticks (diagnostics: where a changed run first departs). */
  checkpoints: Array<{ tick: number; hash: string }>;
}

/** Runs a scenario's golden script with default parameters and returns the final hash. */
export async function runGolden(def: ScenarioDefinition, opts: { ticks?: number; bots?: number; seed?: number; worldOptions?: PhysicsWorldOptions } = {}): Promise<GoldenResult> {
  const ticks = opts.ticks ?? def.golden?.ticks;
  const bots = opts.bots ?? def.golden?.bots;
  const seed = opts.seed ?? GOLDEN_SEED;
  if (!Number.isInteger(ticks) || ticks! < 1) throw new Error(`scenario ${def.name}: golden.ticks must be an integer >= 1`);
  if (!Number.isInteger(bots) || bots! < 0) throw new Error(`scenario ${def.name}: golden.bots must be an integer >= 0`);
  const sim = await Simulation.create({ scenario: def, seed, worldOptions: opts.worldOptions });
  try {
    const script = new BotScript({ seed, bots: bots!, joinSpacingTicks: GOLDEN_JOIN_SPACING_TICKS });
    const checkpoints: Array<{ tick: number; hash: string }> = [];
    for (let t = 0; t < ticks!; t++) {
      sim.step(script.next());
      if (sim.tick % GOLDEN_HASH_EVERY_TICKS === 0) checkpoints.push({ tick: sim.tick, hash: sim.stateHash() });
    }
    return { scenario: def.name, ticks: ticks!, bots: bots!, seed, hash: sim.stateHash(), checkpoints };
  } finally {
    sim.destroy();
  }
}

/** Checks parsed JSON against the GoldenFile shape; throws a clear Error naming the bad field. */
export function parseGoldenFile(raw: unknown, where: string): GoldenFile {
  if (raw === null || typeof raw !== 'object' || Array.isArray(raw)) throw new Error(`${where}: a golden file must hold a JSON object`);
  const g = raw as Record<string, unknown>;
  const str = (k: string): string => {
    if (typeof g[k] !== 'string' || g[k] === '') throw new Error(`${where}: "${k}" must be a non-empty string`);
    return g[k] as string;
  };
  const int = (k: string): number => {
    if (typeof g[k] !== 'number' || !Number.isInteger(g[k]) || (g[k] as number) < 0) throw new Error(`${where}: "${k}" must be a non-negative integer`);
    return g[k] as number;
  };
  const hash = str('hash');
  if (!/^[0-9a-f]{16}$/.test(hash)) throw new Error(`${where}: "hash" must be 16 lowercase hex characters`);
  return { scenario: str('scenario'), ticks: int('ticks'), bots: int('bots'), seed: int('seed'), hash, joltVersion: str('joltVersion') };
}

/** The JSON text stored for a golden result (stable key order, trailing newline). */
export function formatGoldenFile(result: GoldenResult, joltVersion: string): string {
  const file: GoldenFile = { scenario: result.scenario, ticks: result.ticks, bots: result.bots, seed: result.seed, hash: result.hash, joltVersion };
  return `${JSON.stringify(file, null, 2)}\n`;
}
