// Helpers for simulation tests: create a simulation of a test scenario, build records, run and collect hashes.
import '../../../../server/physics-node.ts';
import { BotScript } from '../../../../shared/sim/bots.ts';
import type { InputCommand } from '../../../../shared/sim/input.ts';
import type { ScenarioDefinition } from '../../../../shared/sim/scenario.ts';
import { Simulation } from '../../../../shared/sim/simulation.ts';
import type { PlayerCommand, PlayerJoin, SimEvent, TickInputRecord } from '../../../../shared/sim/types.ts';
import { testArena } from './test-scenarios.ts';

/** The idle command. */
export const IDLE: InputCommand = Object.freeze({ moveX: 0, moveZ: 0, yaw: 0, pitch: 0, buttons: 0 });

/** A simulation of `def` (default: the test arena). */
export function makeSim(def: ScenarioDefinition = testArena, params?: Record<string, number>, seed: number | string = 1): Promise<Simulation> {
  return Simulation.create({ scenario: def, params, seed });
}

/** A record for one tick. */
export function record(tick: number, parts: { leaves?: number[]; joins?: PlayerJoin[]; commands?: PlayerCommand[] } = {}): TickInputRecord {
  return { tick, leaves: parts.leaves ?? [], joins: parts.joins ?? [], commands: parts.commands ?? [] };
}

/** `count` records of a seeded bot crowd. */
export function botRecords(count: number, opts: { seed?: number; bots?: number; joinTicks?: number[]; leaveTicks?: number[] } = {}): TickInputRecord[] {
  return new BotScript({ seed: opts.seed ?? 3, bots: opts.bots ?? 3, joinTicks: opts.joinTicks, leaveTicks: opts.leaveTicks, joinSpacingTicks: 20 }).take(count);
}

/** Steps every record and returns the hash after each. */
export function runHashes(sim: Simulation, records: readonly TickInputRecord[], events?: SimEvent[]): string[] {
  const out: string[] = [];
  for (const r of records) {
    const ev = sim.step(r);
    if (events) events.push(...ev);
    out.push(sim.stateHash());
  }
  return out;
}

/** Steps `n` empty ticks. */
export function idleTicks(sim: Simulation, n: number): void {
  for (let i = 0; i < n; i++) sim.step(record(sim.tick));
}
