// The interpolation buffer: holds decoded snapshots by tick and, at any local time, produces the world as of a render
// tick that trails the arrivals by an adaptive delay (two snapshot intervals plus measured arrival jitter). Positions
// lerp, rotations slerp on the shortest path; late snapshots mean bounded extrapolation, then hold. Client-only code.
import type { SnapshotView } from '../shared/protocol/snapshot-frame.ts';
import type { CharacterState } from '../shared/sim/types.ts';

/** Options of InterpolationBuffer. */
export interface InterpolationOptions {
  tickRateHz: number;
  /** The server's snapshot rate (welcome.snapshotRateHz). */
  snapshotRateHz: number;
  /** Snapshot intervals of delay before jitter is added. Default 2. */
  delayIntervals?: number;
  /** Bounds on the delay (ms). Defaults 0 and 1000. */
  minDelayMs?: number;
  maxDelayMs?: number;
  /** Longest extrapolation past the newest snapshot before holding (ms). Default 100. */
  maxExtrapolationMs?: number;
  /** Most snapshots buffered. Default 120. */
  capacity?: number;
  /** Arrivals considered for the delay base and jitter (ms of history). Default 3000. */
  jitterWindowMs?: number;
}

/** What sample() did: nothing yet, held before the first snapshot, between two, past the newest, or held. */
export type InterpolationMode = 'empty' | 'waiting' | 'interpolating' | 'extrapolating' | 'holding';

/** The world to draw at one local time. */
export interface InterpolatedFrame {
  /** The interpolated world (a fresh object per call), or null before any snapshot. */
  view: SnapshotView | null;
  /** The fractional server tick shown. */
  renderTick: number;
  mode: InterpolationMode;
  /** Snapshots buffered with a tick after the render tick. */
  bufferDepth: number;
  /** How far the render tick trails the newest tick expected to have arrived (ms). */
  delayMs: number;
  /** The delay the buffer steers towards (ms). */
  targetDelayMs: number;
  /** Arrival jitter: 90th percentile of lateness against the earliest arrivals (ms). */
  jitterMs: number;
  /** Ticks extrapolated past the newest snapshot (0 unless extrapolating or holding). */
  extrapolatedTicks: number;
}

/** What push() did with a snapshot. */
export type PushOutcome = 'stored' | 'duplicate' | 'late';

/** Counters of InterpolationBuffer. */
export interface InterpolationStats {
  stored: number;
  duplicates: number;
  late: number;
  /** Stored snapshots that arrived after a newer one. */
  reordered: number;
  /** Snapshots dropped because the buffer was full. */
  overflow: number;
}

/** Buffers snapshots and samples them at a smoothly advancing render tick. */
export class InterpolationBuffer {
  readonly tickMs: number;
  readonly intervalMs: number;
  private readonly delayIntervals: number;
  private readonly minDelayMs: number;
  private readonly maxDelayMs: number;
  private readonly maxExtrapolationTicks: number;
  private readonly capacity: number;
  private readonly jitterWindowMs: number;
  private entries: SnapshotView[] = [];
  private arrivals: Array<{ atMs: number; offsetMs: number }> = [];
  private baseMs = 0;
  private jitter = 0;
  private renderTick: number | null = null;
  private lastSampleMs = 0;
  private newestTick = -1;
  readonly stats: InterpolationStats = { stored: 0, duplicates: 0, late: 0, reordered: 0, overflow: 0 };

  constructor(opts: InterpolationOptions) {
    if (!(opts.tickRateHz > 0) || !(opts.snapshotRateHz > 0)) throw new Error('InterpolationBuffer: tickRateHz and snapshotRateHz must be > 0');
    this.tickMs = 1000 / opts.tickRateHz;
    this.intervalMs = 1000 / Math.min(opts.snapshotRateHz, opts.tickRateHz);
    this.delayIntervals = opts.delayIntervals ?? 2;
    this.minDelayMs = opts.minDelayMs ?? 0;
    this.maxDelayMs = opts.maxDelayMs ?? 1000;
    this.maxExtrapolationTicks = (opts.maxExtrapolationMs ?? 100) / this.tickMs;
    this.capacity = opts.capacity ?? 120;
    this.jitterWindowMs = opts.jitterWindowMs ?? 3000;
    if (!(this.delayIntervals >= 0) || !(this.maxDelayMs >= this.minDelayMs) || !(this.maxExtrapolationTicks >= 0) || !(this.capacity >= 2)) {
      throw new Error('InterpolationBuffer: need delayIntervals ≥ 0, minDelayMs ≤ maxDelayMs, maxExtrapolationMs ≥ 0, capacity ≥ 2');
    }
  }

  /** Snapshots held. */
  get size(): number {
    return this.entries.length;
  }

  /** The delay the buffer aims for now (ms): delayIntervals × interval + jitter, clamped. */
  get targetDelayMs(): number {
    return Math.min(this.maxDelayMs, Math.max(this.minDelayMs, this.delayIntervals * this.intervalMs + this.jitter));
  }

  /** Adds a decoded snapshot that arrived at local time `arrivalMs`. Duplicates and snapshots older than the render point are refused. */
  push(view: SnapshotView, arrivalMs: number): PushOutcome {
    const i = this.findIndex(view.tick);
    if (i >= 0 && this.entries[i].tick === view.tick) {
      this.stats.duplicates++;
      return 'duplicate';
    }
    const lower = this.renderTick === null ? -1 : this.lowerIndex(this.renderTick);
    if (lower >= 0 && view.tick < this.entries[lower].tick) {
      this.stats.late++;
      this.noteArrival(view.tick, arrivalMs);
      return 'late';
    }
    this.entries.splice(i + 1, 0, view);
    if (view.tick < this.newestTick) this.stats.reordered++;
    this.newestTick = Math.max(this.newestTick, view.tick);
    this.stats.stored++;
    this.noteArrival(view.tick, arrivalMs);
    while (this.entries.length > this.capacity) {
      this.entries.shift();
      this.stats.overflow++;
    }
    return 'stored';
  }

  private noteArrival(tick: number, arrivalMs: number): void {
    this.arrivals.push({ atMs: arrivalMs, offsetMs: arrivalMs - tick * this.tickMs });
    while (this.arrivals.length > 1 && (this.arrivals[0].atMs < arrivalMs - this.jitterWindowMs || this.arrivals.length > 512)) this.arrivals.shift();
    let base = Infinity;
    for (const a of this.arrivals) base = Math.min(base, a.offsetMs);
    this.baseMs = base;
    const lateness = this.arrivals.map((a) => a.offsetMs - base).sort((x, y) => x - y);
    this.jitter = lateness[Math.min(lateness.length - 1, Math.floor(lateness.length * 0.9))];
  }

  /** Index of the last entry with tick ≤ t (−1 if none). */
  private findIndex(t: number): number {
    let lo = 0;
    let hi = this.entries.length - 1;
    let ans = -1;
    while (lo <= hi) {
      const mid = (lo + hi) >> 1;
      if (this.entries[mid].tick <= t) {
        ans = mid;
        lo = mid + 1;
      } else hi = mid - 1;
    }
    return ans;
  }

  private lowerIndex(renderTick: number): number {
    return this.findIndex(renderTick);
  }

  /** The render tick the buffer would show at `nowMs` before smoothing. */
  targetRenderTick(nowMs: number): number {
    return (nowMs - this.baseMs - this.targetDelayMs) / this.tickMs;
  }

  /** The world at local time `nowMs` (call once per rendered frame; time must not go backwards). */
  sample(nowMs: number): InterpolatedFrame {
    if (this.entries.length === 0) {
      return { view: null, renderTick: this.renderTick ?? 0, mode: 'empty', bufferDepth: 0, delayMs: 0, targetDelayMs: this.targetDelayMs, jitterMs: this.jitter, extrapolatedTicks: 0 };
    }
    const target = this.targetRenderTick(nowMs);
    const snapTicks = Math.max(10, (3 * this.intervalMs) / this.tickMs);
    if (this.renderTick === null || Math.abs(target - this.renderTick) > snapTicks) {
      this.renderTick = target;
    } else {
      // Advance with the clock, then steer towards the target by at most 10% of the advance (running up to 10%
      // fast or slow): no visible jumps, never backwards.
      const advance = Math.max(0, nowMs - this.lastSampleMs) / this.tickMs;
      const predicted = this.renderTick + advance;
      const maxCorrection = 0.1 * advance;
      this.renderTick = predicted + Math.max(-maxCorrection, Math.min(maxCorrection, target - predicted));
    }
    this.lastSampleMs = nowMs;
    const rt = this.renderTick;
    const expectedNewest = (nowMs - this.baseMs) / this.tickMs;
    const base = { renderTick: rt, targetDelayMs: this.targetDelayMs, jitterMs: this.jitter, delayMs: (expectedNewest - rt) * this.tickMs };
    const i = this.findIndex(rt);
    if (i < 0) {
      return { ...base, view: copyView(this.entries[0]), mode: 'waiting', bufferDepth: this.entries.length, extrapolatedTicks: 0 };
    }
    // Older snapshots than the one before the render point are no longer needed.
    if (i > 1) {
      this.entries.splice(0, i - 1);
    }
    const ai = Math.min(i, 1);
    const a = this.entries[ai];
    const depth = this.entries.length - ai - 1;
    if (ai + 1 < this.entries.length) {
      const b = this.entries[ai + 1];
      const alpha = (rt - a.tick) / (b.tick - a.tick);
      return { ...base, view: blend(a, b, alpha, rt), mode: 'interpolating', bufferDepth: depth, extrapolatedTicks: 0 };
    }
    const ex = rt - a.tick;
    const clamped = Math.min(ex, this.maxExtrapolationTicks);
    const mode: InterpolationMode = ex <= this.maxExtrapolationTicks ? 'extrapolating' : 'holding';
    if (ai === 0 || clamped <= 0) return { ...base, view: copyView(a), mode: ai === 0 && ex > 0 ? 'holding' : mode, bufferDepth: 0, extrapolatedTicks: 0 };
    const p = this.entries[ai - 1];
    return { ...base, view: blend(p, a, 1 + clamped / (a.tick - p.tick), rt), mode, bufferDepth: 0, extrapolatedTicks: clamped };
  }

  /** Forgets all snapshots and timing (a new connection). */
  reset(): void {
    this.entries = [];
    this.arrivals = [];
    this.baseMs = 0;
    this.jitter = 0;
    this.renderTick = null;
    this.newestTick = -1;
  }
}

function copyView(v: SnapshotView): SnapshotView {
  return { tick: v.tick, ids: v.ids.slice(), positions: v.positions.slice(), rotations: v.rotations.slice(), atRest: v.atRest.slice(), characters: v.characters.map(copyCharacter) };
}

function copyCharacter(c: CharacterState): CharacterState {
  return { ...c, position: { ...c.position }, velocity: { ...c.velocity } };
}

/**
 * Bodies of `a` moved towards their pose in `b` by t (t in [0, 1] interpolates, t > 1 extrapolates along the same
 * motion). Bodies missing from b keep a's pose (their removal shows at b's tick); bodies only in b are not shown yet.
 * When extrapolating (t > 1) the roles are: a = older, b = newest, and the set shown is b's.
 */
function blend(a: SnapshotView, b: SnapshotView, t: number, renderTick: number): SnapshotView {
  const extrapolating = t > 1;
  const from = extrapolating ? b : a;
  const other = extrapolating ? a : b;
  const n = from.ids.length;
  const ids = from.ids.slice();
  const positions = new Float32Array(n * 3);
  const rotations = new Float32Array(n * 4);
  const atRest = from.atRest.slice();
  let j = 0;
  for (let i = 0; i < n; i++) {
    const id = from.ids[i];
    while (j < other.ids.length && other.ids[j] < id) j++;
    const matched = j < other.ids.length && other.ids[j] === id;
    const pi = i * 3;
    const qi = i * 4;
    if (!matched || (extrapolating && from.atRest[i] === 1)) {
      positions.set(from.positions.subarray(pi, pi + 3), pi);
      rotations.set(from.rotations.subarray(qi, qi + 4), qi);
      continue;
    }
    // Always blend older → newer with weight t (a is older in both cases).
    const oi = extrapolating ? j : i;
    const ni = extrapolating ? i : j;
    for (let k = 0; k < 3; k++) {
      const p0 = a.positions[oi * 3 + k];
      const p1 = b.positions[ni * 3 + k];
      positions[pi + k] = p0 + (p1 - p0) * t;
    }
    slerpInto(a.rotations, oi * 4, b.rotations, ni * 4, t, rotations, qi);
    if (!extrapolating) atRest[i] = a.atRest[i] === 1 && b.atRest[j] === 1 ? 1 : 0;
  }
  return { tick: Math.floor(renderTick), ids, positions, rotations, atRest, characters: blendCharacters(a.characters, b.characters, t) };
}

/** Shortest-path spherical interpolation (or extrapolation for t > 1) of two unit quaternions into out. */
export function slerpInto(qa: ArrayLike<number>, ia: number, qb: ArrayLike<number>, ib: number, t: number, out: Float32Array, io: number): void {
  const ax = qa[ia];
  const ay = qa[ia + 1];
  const az = qa[ia + 2];
  const aw = qa[ia + 3];
  let bx = qb[ib];
  let by = qb[ib + 1];
  let bz = qb[ib + 2];
  let bw = qb[ib + 3];
  let dot = ax * bx + ay * by + az * bz + aw * bw;
  if (dot < 0) {
    dot = -dot;
    bx = -bx;
    by = -by;
    bz = -bz;
    bw = -bw;
  }
  let wa: number;
  let wb: number;
  if (dot > 0.9995) {
    wa = 1 - t;
    wb = t;
  } else {
    const theta = Math.acos(Math.min(1, dot));
    const s = Math.sin(theta);
    wa = Math.sin((1 - t) * theta) / s;
    wb = Math.sin(t * theta) / s;
  }
  const x = ax * wa + bx * wb;
  const y = ay * wa + by * wb;
  const z = az * wa + bz * wb;
  const w = aw * wa + bw * wb;
  const len = Math.hypot(x, y, z, w) || 1;
  out[io] = x / len;
  out[io + 1] = y / len;
  out[io + 2] = z / len;
  out[io + 3] = w / len;
}

function wrapAngle(r: number): number {
  const twoPi = 2 * Math.PI;
  return ((r % twoPi) + twoPi) % twoPi;
}

function blendCharacters(a: readonly CharacterState[], b: readonly CharacterState[], t: number): CharacterState[] {
  const extrapolating = t > 1;
  const shown = extrapolating ? b : a;
  const byPlayer = new Map<number, CharacterState>();
  for (const c of extrapolating ? a : b) byPlayer.set(c.playerId, c);
  return shown.map((c) => {
    const o = byPlayer.get(c.playerId);
    if (o === undefined) return copyCharacter(c);
    const older = extrapolating ? o : c;
    const newer = extrapolating ? c : o;
    const lerp = (x: number, y: number): number => x + (y - x) * t;
    let dYaw = newer.yaw - older.yaw;
    dYaw = ((((dYaw + Math.PI) % (2 * Math.PI)) + 2 * Math.PI) % (2 * Math.PI)) - Math.PI;
    return {
      ...c,
      position: { x: lerp(older.position.x, newer.position.x), y: lerp(older.position.y, newer.position.y), z: lerp(older.position.z, newer.position.z) },
      velocity: { x: lerp(older.velocity.x, newer.velocity.x), y: lerp(older.velocity.y, newer.velocity.y), z: lerp(older.velocity.z, newer.velocity.z) },
      yaw: wrapAngle(older.yaw + dYaw * t),
      pitch: lerp(older.pitch, newer.pitch),
    };
  });
}
