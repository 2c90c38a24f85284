// What a room costs its thread per tick: the worker's measurement once the room has ticked, a per-scenario estimate
// before that, and the budget a room worker fills before it counts as full.
import { TICK_MS } from '../../shared/tick-rate.ts';
import type { RemoteRoom } from './remote-room.ts';

/** The share of every tick period a worker may fill with room ticks (the rest absorbs GC and jitter). */
export const WORKER_BUDGET_MS_PER_TICK = TICK_MS * 0.75;

/** Estimated CPU ms per tick of a room that has not ticked yet, by scenario (linear in what it simulates). */
const ESTIMATES: Readonly<Record<string, (p: Readonly<Record<string, number>>) => number>> = {
  'character-course': () => 0.4,
  'shape-rain': (p) => 0.3 + (p.count ?? 300) * 0.0025 * ((p.sizeMetres ?? 0.35) / 0.35) ** 2,
  'height-field': (p) => 0.3 + (p.bodyCount ?? 80) * 0.007 + ((p.samplesPerSide ?? 64) / 256) ** 2,
  'convex-hulls': (p) => 0.2 + ((p.count ?? 150) * 0.004 * (p.maxPoints ?? 24)) / 8,
  'mesh-terrain': (p) => 0.3 + (p.bodyCount ?? 80) * 0.005,
  'pendulum-chain': () => 0.8,
  'terrain-balls': () => 2,
  'cubes-901': () => 2.5,
  'crowd-arena': (p) => 0.2 + (p.props ?? 256) * 0.0005,
};

/** A room of an unknown scenario counts as this many ms per tick until measured. */
const UNKNOWN_SCENARIO_MS = 1;

/** The estimated ms per tick of a new room of `scenario` with these (resolved) parameters. */
export function estimateTickCpuMs(scenario: string, params: Readonly<Record<string, number>>): number {
  const estimate = ESTIMATES[scenario];
  return estimate ? estimate(params) : UNKNOWN_SCENARIO_MS;
}

/** A room's cost: measured when it has ticked, else its scenario's estimate. */
export function roomTickCpuMs(room: RemoteRoom): number {
  return room.status?.tickCpuMs ?? estimateTickCpuMs(room.scenarioName, room.params);
}

/** What placement needs to know of one worker. */
export interface WorkerHeadroom {
  worker: number;
  rooms: number;
  /** Budget left: the worker's budget minus its rooms' CPU ms per tick. */
  headroomMs: number;
}

/**
 * Where a new room needing `needMs` per tick goes: the worker with the most headroom when that is enough; else a worker
 * with no room at all (a room heavier than a worker's budget gets a thread of its own and slows only itself); else
 * nowhere, with the reason for a 503.
 */
export function placeRoom(workers: readonly WorkerHeadroom[], needMs: number, scenario: string, budgetMs: number): { worker: number } | { refusal: string } {
  if (workers.length === 0) return { refusal: 'no room worker is running (one is being restarted); try again shortly' };
  const best = workers.reduce((a, b) => (b.headroomMs > a.headroomMs ? b : a));
  if (best.headroomMs >= needMs) return { worker: best.worker };
  const idle = workers.find((w) => w.rooms === 0);
  if (idle) return { worker: idle.worker };
  return {
    refusal: `no capacity for another ${scenario} room: it needs about ${needMs.toFixed(1)} ms of CPU per tick and the most any room worker has left is ${Math.max(0, best.headroomMs).toFixed(1)} ms (of ${budgetMs.toFixed(1)} ms per tick on each of ${workers.length} workers)`,
  };
}
