// Which room moves where when a room worker is over its budget because one of its rooms proved much heavier than
// its estimate and the rooms beside it miss their budget: the heavy room to a worker with headroom (or an idle one),
// else the light rooms away from it. Pure and deterministic; the pool applies at most one move at a time.

/** A room as the policy sees it. */
export interface PolicyRoom {
  id: string;
  /** Its CPU ms per tick: measured once it has ticked, else the estimate. */
  costMs: number;
  /** Its scenario's estimate (what placement assumed). */
  estimateMs: number;
  /** Whether costMs is a measurement. */
  measured: boolean;
  /** It cannot keep 60 Hz (it gave up ticks lately). */
  missingBudget: boolean;
}

/** A worker and its rooms. */
export interface PolicyWorker {
  worker: number;
  rooms: readonly PolicyRoom[];
}

/** One move to make. */
export interface MovePlan {
  room: string;
  from: number;
  to: number;
  /** Why, for logs and /api/rooms. */
  reason: string;
}

/** A measured room counts as heavier than estimated from this multiple of its estimate… */
export const HEAVIER_FACTOR = 2;
/** …and this many ms per tick above it. */
export const HEAVIER_MARGIN_MS = 1;

const load = (w: PolicyWorker): number => w.rooms.reduce((sum, r) => sum + r.costMs, 0);
const byId = (a: PolicyRoom, b: PolicyRoom): number => (a.id < b.id ? -1 : a.id > b.id ? 1 : 0);

/** Whether a room's measurement proves it much heavier than its estimate. */
export function provedHeavier(room: PolicyRoom): boolean {
  return room.measured && room.costMs >= HEAVIER_FACTOR * room.estimateMs && room.costMs - room.estimateMs >= HEAVIER_MARGIN_MS;
}

/**
 * The next move, or null: for the first worker (by index) over `budgetMs` where a room proved much heavier than its
 * estimate and a room beside it misses its budget, the heaviest such room goes to the worker with the most headroom
 * that fits it, else to an idle worker; when neither exists, the neighbour missing its budget that frees the most and
 * fits elsewhere goes instead. Rooms in `skip` (moved lately) stay.
 */
export function planMove(workers: readonly PolicyWorker[], budgetMs: number, skip: ReadonlySet<string> = new Set()): MovePlan | null {
  const sorted = [...workers].sort((a, b) => a.worker - b.worker);
  for (const w of sorted) {
    const loadMs = load(w);
    if (loadMs <= budgetMs) continue;
    const heavy = w.rooms
      .filter((r) => provedHeavier(r) && !skip.has(r.id))
      .sort((a, b) => b.costMs - b.estimateMs - (a.costMs - a.estimateMs) || byId(a, b))[0];
    if (!heavy) continue;
    const starved = w.rooms.filter((r) => r !== heavy && r.missingBudget);
    if (starved.length === 0) continue;
    const others = sorted.filter((o) => o.worker !== w.worker).map((o) => ({ worker: o.worker, rooms: o.rooms.length, headroomMs: budgetMs - load(o) }));
    const fits = (needMs: number): number | null => {
      let best: { worker: number; headroomMs: number } | null = null;
      for (const o of others) if (o.headroomMs >= needMs && (best === null || o.headroomMs > best.headroomMs)) best = o;
      return best?.worker ?? null;
    };
    const why = `room ${heavy.id} uses ${heavy.costMs.toFixed(1)} ms per tick (estimated ${heavy.estimateMs.toFixed(1)}); worker ${w.worker} is at ${loadMs.toFixed(1)} of ${budgetMs.toFixed(1)} ms and ${starved.map((r) => r.id).join(', ')} miss their budget`;
    const target = fits(heavy.costMs) ?? others.find((o) => o.rooms === 0)?.worker ?? null;
    if (target !== null) return { room: heavy.id, from: w.worker, to: target, reason: `${why}: moving it` };
    for (const light of starved.filter((r) => !skip.has(r.id)).sort((a, b) => b.costMs - a.costMs || byId(a, b))) {
      const to = fits(light.costMs);
      if (to !== null) return { room: light.id, from: w.worker, to, reason: `${why}: no worker fits it, moving ${light.id} away from it` };
    }
  }
  return null;
}
