// Scenario checks through the real Simulation: seeded bots drive a scenario in several simulations that must agree
// hash for hash, including across a fast checkpoint rollback and a byte checkpoint restored into a fresh simulation.
import { expect } from 'vitest';
import '../../server/physics-node.ts';
import { BotScript } from '../../shared/sim/bots.ts';
import type { ScenarioDefinition } from '../../shared/sim/scenario.ts';
import { Simulation } from '../../shared/sim/simulation.ts';
import type { SimEvent, TickInputRecord } from '../../shared/sim/types.ts';

/** The bot records of a run: `bots` seeded bots joining 5 ticks apart. */
export function botRecords(seed: number, bots: number, ticks: number): TickInputRecord[] {
  const script = new BotScript({ seed, bots, joinSpacingTicks: 5 });
  return Array.from({ length: ticks }, () => script.next());
}

/** Steps `sim` through `records`, returning the state hash after each. */
export function hashesOf(sim: Simulation, records: readonly TickInputRecord[], events?: SimEvent[]): string[] {
  return records.map((r) => {
    const ev = sim.step(r);
    events?.push(...ev);
    return sim.stateHash();
  });
}

/**
 * Runs `def` with `params` under bots for `ticks` ticks and expects: two simulations agree every tick; a rollback to
 * a mid-run checkpoint and a byte checkpoint restored into a fresh simulation both replay the same hashes; another
 * seed ends elsewhere. Returns the run's events.
 */
export async function expectSimulationReplays(def: ScenarioDefinition, params: Record<string, number>, ticks: number, bots: number): Promise<SimEvent[]> {
  const seed = 5;
  const records = botRecords(seed, bots, ticks);
  const mid = Math.floor(ticks / 2);
  const events: SimEvent[] = [];
  const a = await Simulation.create({ scenario: def, params, seed });
  const b = await Simulation.create({ scenario: def, params, seed });
  const fresh = await Simulation.create({ scenario: def, params, seed });
  const other = await Simulation.create({ scenario: def, params, seed: seed + 1 });
  try {
    const expected = hashesOf(a, records, events);
    expect(new Set(expected).size).toBeGreaterThan(ticks / 2);
    hashesOf(b, records.slice(0, mid)).forEach((h, i) => expect(h, `tick ${i}`).toBe(expected[i]));
    const cp = b.saveCheckpoint();
    const bytes = b.saveCheckpointBytes();
    try {
      expect(hashesOf(b, records.slice(mid))).toEqual(expected.slice(mid));
      b.restoreCheckpoint(cp);
      expect(b.tick).toBe(mid);
      expect(hashesOf(b, records.slice(mid))).toEqual(expected.slice(mid));
    } finally {
      cp.dispose();
    }
    fresh.restoreCheckpointBytes(bytes);
    expect(hashesOf(fresh, records.slice(mid))).toEqual(expected.slice(mid));
    const theirs = botRecords(seed + 1, bots, ticks);
    expect(hashesOf(other, theirs).at(-1)).not.toBe(expected.at(-1));
    return events;
  } finally {
    a.destroy();
    b.destroy();
    fresh.destroy();
    other.destroy();
  }
}
