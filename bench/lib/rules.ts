// The bench's pass rules and derived figures, as pure functions over measured numbers: when a client count or a room
// count passes, the per-client cost line, GC pause per tick, and an input-latency distribution that keeps late inputs.
import { linearFit, quantile } from './stats.ts';

/** The server's tick rate. */
export const TICK_RATE_HZ = 60;
/** One tick's budget (ms). */
export const TICK_BUDGET_MS = 1000 / TICK_RATE_HZ;
/** A window keeps up when it ran at least this share of the ticks wall time asked for. */
export const MIN_TICK_RATE_SHARE = 0.99;
/** Most snapshots a passing client step may skip (backed-up sockets). */
export const MAX_SKIPPED_SNAPSHOT_SHARE = 0.01;
/** Longest gap between two tick starts of one room a passing room step may show, in ticks. */
export const MAX_ROOM_TICK_GAP_TICKS = 2;

/** A clients-per-core measurement window, as the server and the bots saw it. */
export interface ClientWindow {
  seconds: number;
  /** Room ticks run in the window. */
  ticks: number;
  /** p99 of the room's tick times (ms); null when no tick ran. */
  tickP99Ms: number | null;
  snapshotsSent: number;
  snapshotsSkipped: number;
  /** Clients the server dropped or that closed. */
  droppedClients: number;
}

/** A verdict with the reasons for a miss (empty when it passes). */
export interface Verdict {
  pass: boolean;
  reasons: string[];
}

/** A client count passes at 60 ticks/s (≥ 99% of the window's ticks ran), tick p99 < 16.7 ms, ≤ 1% skipped snapshots, nobody dropped. */
export function judgeClientWindow(w: ClientWindow): Verdict {
  const reasons: string[] = [];
  const ticksPerSecond = w.seconds > 0 ? w.ticks / w.seconds : 0;
  if (!(ticksPerSecond >= TICK_RATE_HZ * MIN_TICK_RATE_SHARE)) reasons.push(`${ticksPerSecond.toFixed(1)} ticks/s < ${TICK_RATE_HZ}`);
  if (w.tickP99Ms === null || !(w.tickP99Ms < TICK_BUDGET_MS)) reasons.push(`tick p99 ${w.tickP99Ms === null ? 'n/a' : w.tickP99Ms.toFixed(1)} ms ≥ ${TICK_BUDGET_MS.toFixed(1)} ms`);
  const offered = w.snapshotsSent + w.snapshotsSkipped;
  const skippedShare = offered > 0 ? w.snapshotsSkipped / offered : 1;
  if (skippedShare > MAX_SKIPPED_SNAPSHOT_SHARE) reasons.push(offered > 0 ? `${(skippedShare * 100).toFixed(1)}% of snapshots skipped` : 'no snapshots sent');
  if (w.droppedClients > 0) reasons.push(`${w.droppedClients} clients dropped`);
  return { pass: reasons.length === 0, reasons };
}

/** One room in a rooms-per-core window, as the server and its clients saw it. */
export interface RoomWindow {
  id: string;
  ticks: number;
  /** Longest gap between two consecutive tick starts (ms); null when fewer than two ticks ran. */
  maxGapMs: number | null;
  /** p99 of its tick times (ms); null when not measured. */
  tickP99Ms: number | null;
  /** Players in the room at the end of the window. */
  clients: number;
  /** Snapshots its clients received in the window. */
  snapshots: number;
  /** Longest time between two snapshots arriving at one of its clients (ms); null when none saw two. */
  clientGapMs: number | null;
  /** Largest step between the ticks of two snapshots one of its clients received in a row; null when none saw two. */
  clientTickStep: number | null;
}

/** What a rooms window is judged against. */
export interface RoomsRule {
  /** Players each room must hold (more means players of an earlier step were left in it; fewer, some dropped). */
  botsPerRoom: number;
  /** Ticks between two snapshots (2 at 30 Hz snapshots). */
  snapshotIntervalTicks: number;
}

/** Longest a client may wait between two snapshots (ms): their spacing plus 2 ticks. */
export function maxClientGapMs(snapshotIntervalTicks: number): number {
  return (snapshotIntervalTicks + MAX_ROOM_TICK_GAP_TICKS) * TICK_BUDGET_MS;
}

/**
 * A room count holds when every room ran ≥ 99% of 60 ticks/s with tick p99 < 16.7 ms, its tick starts at most 2 ticks
 * apart, the expected players in it, and its clients saw every snapshot (tick steps of one snapshot interval) with no
 * wait longer than the interval plus 2 ticks.
 */
export function judgeRoomsWindow(seconds: number, rooms: readonly RoomWindow[], rule: RoomsRule): Verdict {
  const reasons: string[] = [];
  if (rooms.length === 0) reasons.push('no rooms');
  const count = (what: string, bad: readonly RoomWindow[], worst?: string): void => {
    if (bad.length > 0) reasons.push(`${bad.length} room(s) ${what}${worst ? ` (worst ${worst})` : ''}`);
  };
  const wanted = seconds * TICK_RATE_HZ * MIN_TICK_RATE_SHARE;
  count(`below ${TICK_RATE_HZ} ticks/s`, rooms.filter((r) => !(r.ticks >= wanted)));
  const worstMs = (bad: readonly RoomWindow[], pick: (r: RoomWindow) => number | null): string => {
    const worst = Math.max(...bad.map((r) => pick(r) ?? Infinity));
    return Number.isFinite(worst) ? `${worst.toFixed(1)} ms` : 'not measured';
  };
  const slowP99 = rooms.filter((r) => r.tickP99Ms === null || !(r.tickP99Ms < TICK_BUDGET_MS));
  count(`with tick p99 ≥ ${TICK_BUDGET_MS.toFixed(1)} ms`, slowP99, worstMs(slowP99, (r) => r.tickP99Ms));
  const limitMs = MAX_ROOM_TICK_GAP_TICKS * TICK_BUDGET_MS;
  const gapped = rooms.filter((r) => r.maxGapMs === null || r.maxGapMs > limitMs);
  count(`with a tick gap > ${MAX_ROOM_TICK_GAP_TICKS} ticks`, gapped, worstMs(gapped, (r) => r.maxGapMs));
  const crowded = rooms.filter((r) => r.clients !== rule.botsPerRoom);
  count(`without exactly ${rule.botsPerRoom} players`, crowded, undefined);
  const skipped = rooms.filter((r) => r.clientTickStep === null || r.clientTickStep > rule.snapshotIntervalTicks);
  count('whose clients missed a snapshot', skipped, undefined);
  const clientLimitMs = maxClientGapMs(rule.snapshotIntervalTicks);
  const waited = rooms.filter((r) => r.clientGapMs === null || r.clientGapMs > clientLimitMs);
  count(`whose clients waited > ${clientLimitMs.toFixed(1)} ms for a snapshot`, waited, worstMs(waited, (r) => r.clientGapMs));
  return { pass: reasons.length === 0, reasons };
}

/** The longest gap between consecutive values of ascending times (ms); null for fewer than two. */
export function maxGap(timesMs: readonly number[]): number | null {
  if (timesMs.length < 2) return null;
  let gap = 0;
  for (let i = 1; i < timesMs.length; i++) gap = Math.max(gap, timesMs[i] - timesMs[i - 1]);
  return gap;
}

/** A GC pause as perf_hooks reports it (ms on the performance clock). */
export interface GcPause {
  startTime: number;
  duration: number;
  /** Whether it was a full (mark-compact) collection; absent when not known. */
  major?: boolean;
}

/**
 * GC pause time per tick-length interval of [fromMs, toMs): each pause counts in the interval it started in (a pause
 * longer than a tick stays whole in one interval: that tick is the one that stalled). Pauses outside are ignored.
 */
export function gcPausePerTick(fromMs: number, toMs: number, pauses: readonly GcPause[], tickMs = TICK_BUDGET_MS): number[] {
  if (!(toMs > fromMs) || !(tickMs > 0)) throw new Error(`gcPausePerTick: needs toMs > fromMs and tickMs > 0 (got ${fromMs}, ${toMs}, ${tickMs})`);
  const out = new Array<number>(Math.max(1, Math.floor((toMs - fromMs) / tickMs))).fill(0);
  for (const p of pauses) {
    if (p.startTime < fromMs || p.startTime >= toMs) continue;
    const i = Math.min(out.length - 1, Math.floor((p.startTime - fromMs) / tickMs));
    out[i] += p.duration;
  }
  return out;
}

/** A measured span on the performance clock (ms), e.g. one server tick. */
export interface Span {
  startMs: number;
  endMs: number;
}

/**
 * GC pause time inside each span: a pause counts in the span it started in ([startMs, endMs)), whole; pauses that
 * started between spans are left out. Spans must be sorted and not overlap.
 */
export function gcPauseInSpans(spans: readonly Span[], pauses: readonly GcPause[]): number[] {
  const out = new Array<number>(spans.length).fill(0);
  const sorted = pauses.slice().sort((a, b) => a.startTime - b.startTime);
  let j = 0;
  for (let i = 0; i < spans.length; i++) {
    const s = spans[i];
    if (i > 0 && s.startMs < spans[i - 1].endMs) throw new Error(`gcPauseInSpans: span ${i} starts before span ${i - 1} ends`);
    while (j < sorted.length && sorted[j].startTime < s.startMs) j++;
    while (j < sorted.length && sorted[j].startTime < s.endMs) out[i] += sorted[j++].duration;
  }
  return out;
}

/** Per-client cost from (clients, server CPU ms per tick) points: ms per tick = fixedMs + clients · usPerClient / 1000. */
export interface ClientCost {
  usPerClientTick: number;
  fixedMsPerTick: number;
  r2: number;
  points: number;
}

/** Least-squares line through the points; null with fewer than two distinct client counts. */
export function clientCost(points: ReadonlyArray<{ clients: number; cpuMsPerTick: number }>): ClientCost | null {
  if (new Set(points.map((p) => p.clients)).size < 2) return null;
  const fit = linearFit(
    points.map((p) => p.clients),
    points.map((p) => p.cpuMsPerTick),
  );
  return { usPerClientTick: fit.slope * 1000, fixedMsPerTick: fit.intercept, r2: fit.r2, points: fit.points };
}

/** Arrival-to-apply waits with the inputs that were never applied (late, or too far ahead) kept in. */
export interface LatencyDistribution {
  /** Every input's first arrival. */
  inputs: number;
  applied: number;
  /** Never applied: they arrived after their tick ran (the server repeated the previous command) or too far ahead. */
  notApplied: number;
  notAppliedShare: number;
  /** Quantiles over every input, unapplied ones ranked after the slowest applied one; null where a quantile lands on one. */
  median: number | null;
  p90: number | null;
  p99: number | null;
  max: number | null;
  /** Count per wait in ticks, and 'late' for the unapplied. */
  histogram: Record<string, number>;
}

/** Builds the distribution from the applied inputs' waits (ticks) and the count never applied. */
export function latencyDistribution(appliedWaits: readonly number[], notApplied: number): LatencyDistribution {
  if (!Number.isInteger(notApplied) || notApplied < 0) throw new Error(`latencyDistribution: notApplied must be a count, got ${notApplied}`);
  const sorted = [...appliedWaits].sort((a, b) => a - b);
  const n = sorted.length + notApplied;
  const at = (q: number): number | null => {
    if (n === 0) return null;
    const pos = (n - 1) * q;
    const lo = Math.floor(pos);
    const hi = Math.ceil(pos);
    if (hi >= sorted.length) return null;
    return sorted[lo] + (sorted[hi] - sorted[lo]) * (pos - lo);
  };
  const histogram: Record<string, number> = {};
  for (const t of sorted) histogram[String(t)] = (histogram[String(t)] ?? 0) + 1;
  if (notApplied > 0) histogram.late = notApplied;
  return {
    inputs: n,
    applied: sorted.length,
    notApplied,
    notAppliedShare: n > 0 ? notApplied / n : 0,
    median: at(0.5),
    p90: at(0.9),
    p99: at(0.99),
    max: notApplied > 0 ? null : sorted.length > 0 ? quantile(sorted, 1) : null,
    histogram,
  };
}

/** How far the light swarm's load on the server may stray from real clients' and still stand in for them. */
export const SWARM_PROOF_TOLERANCE = 0.1;

/** What a swarm costs the server, per window (medians over repeated windows). */
export interface SwarmLoad {
  /** Server process CPU time per room tick (ms). */
  cpuMsPerTick: number;
  /** Messages the server received per client per second. */
  messagesPerClientPerSecond: number;
  /** Bytes the server received per client per second. */
  bytesPerClientPerSecond: number;
}

/** Light / real for each load measure, and whether every one is within the tolerance. */
export function judgeSwarmProof(real: SwarmLoad, light: SwarmLoad, tolerance = SWARM_PROOF_TOLERANCE): Verdict & { ratios: SwarmLoad } {
  const ratios: SwarmLoad = {
    cpuMsPerTick: light.cpuMsPerTick / real.cpuMsPerTick,
    messagesPerClientPerSecond: light.messagesPerClientPerSecond / real.messagesPerClientPerSecond,
    bytesPerClientPerSecond: light.bytesPerClientPerSecond / real.bytesPerClientPerSecond,
  };
  const reasons: string[] = [];
  for (const [key, r] of Object.entries(ratios) as Array<[keyof SwarmLoad, number]>) {
    if (!(Math.abs(r - 1) <= tolerance)) reasons.push(`${key}: light/real ${Number.isFinite(r) ? r.toFixed(3) : 'n/a'} outside 1 ± ${tolerance}`);
  }
  return { pass: reasons.length === 0, reasons, ratios };
}

/**
 * The next client (or room) count of a ladder search: climb the rungs in order until one misses, then halve the
 * interval between the largest pass below the first miss and that miss down to `resolution`. Null when done.
 */
export function nextLadderCount(ladder: readonly number[], results: ReadonlyMap<number, boolean>, resolution: number): number | null {
  const misses = [...results].filter(([, pass]) => !pass).map(([n]) => n);
  if (misses.length === 0) return ladder.find((n) => !results.has(n)) ?? null;
  const hi = Math.min(...misses);
  const passes = [...results].filter(([n, pass]) => pass && n < hi).map(([n]) => n);
  const lo = passes.length > 0 ? Math.max(...passes) : 0;
  if (hi - lo <= resolution) return null;
  const mid = lo + Math.max(resolution, Math.floor((hi - lo) / 2 / resolution) * resolution);
  return mid < hi && !results.has(mid) ? mid : null;
}

/** The largest passing count below the first miss (0 when none passed). */
export function ladderResult(results: ReadonlyMap<number, boolean>): number {
  const misses = [...results].filter(([, pass]) => !pass).map(([n]) => n);
  const hi = misses.length > 0 ? Math.min(...misses) : Infinity;
  const passes = [...results].filter(([n, pass]) => pass && n < hi).map(([n]) => n);
  return passes.length > 0 ? Math.max(...passes) : 0;
}
