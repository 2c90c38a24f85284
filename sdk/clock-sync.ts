// Clock sync: turns ping/pong samples into RTT, jitter, the server-minus-local clock offset and an estimate of the
// server's (fractional) tick at any local time. The offset comes from the lowest-RTT recent sample (least queueing);
// the tick phase from the server's own clock: serverTimeMs − serverTick·tickMs is smallest right after a tick, among
// the samples since the server last fell behind (a room slowed by load runs fewer ticks than its clock says).

/** How far (ticks) an older sample's tick phase may precede the newest one's and still count. */
const PHASE_SPREAD_TICKS = 2;

/** One pong as the client saw it. */
export interface PongSample {
  /** Local time the ping was sent (echoed by the server). */
  sentLocalMs: number;
  /** Local time the pong arrived. */
  receivedLocalMs: number;
  /** Ticks the server had applied when it answered. */
  serverTick: number;
  /** The server's monotonic clock when it answered (ms). */
  serverTimeMs: number;
}

interface Sample {
  rttMs: number;
  /** Server clock minus local clock, assuming symmetric paths. */
  offsetMs: number;
  /** Server time at which tick 0 would have completed, from this sample: serverTimeMs − serverTick·tickMs. */
  anchorMs: number;
}

/** Options of ClockSync. */
export interface ClockSyncOptions {
  tickRateHz: number;
  /** Recent samples kept for the minimum-RTT and phase estimates. Default 12. */
  windowSize?: number;
}

/** Estimates the server clock and tick from pongs; before any pong, from the welcome. */
export class ClockSync {
  readonly tickMs: number;
  private readonly windowSize: number;
  private samples: Sample[] = [];
  private smoothedRtt: number | null = null;
  /** Local time at which the server's tick count was 0, by the current estimate. */
  private originLocalMs: number | null = null;
  private rejected = 0;

  constructor(opts: ClockSyncOptions) {
    if (!(opts.tickRateHz > 0) || !Number.isFinite(opts.tickRateHz)) throw new Error(`ClockSync: tickRateHz must be > 0, got ${opts.tickRateHz}`);
    this.tickMs = 1000 / opts.tickRateHz;
    this.windowSize = opts.windowSize ?? 12;
    if (!Number.isInteger(this.windowSize) || this.windowSize < 1) throw new Error(`ClockSync: windowSize must be a positive integer, got ${opts.windowSize}`);
  }

  /** A first, rough estimate: the welcome said `tick` and arrived at `receivedLocalMs` (one-way delay unknown). */
  seed(tick: number, receivedLocalMs: number): void {
    if (this.samples.length === 0) this.originLocalMs = receivedLocalMs - tick * this.tickMs;
  }

  /** Adds a pong; samples with a negative RTT or non-finite numbers are ignored (returns false). */
  addSample(p: PongSample): boolean {
    const rtt = p.receivedLocalMs - p.sentLocalMs;
    if (!Number.isFinite(rtt) || rtt < 0 || !Number.isFinite(p.serverTimeMs) || !Number.isFinite(p.serverTick)) {
      this.rejected++;
      return false;
    }
    this.samples.push({ rttMs: rtt, offsetMs: p.serverTimeMs - (p.sentLocalMs + p.receivedLocalMs) / 2, anchorMs: p.serverTimeMs - p.serverTick * this.tickMs });
    if (this.samples.length > this.windowSize) this.samples.shift();
    this.smoothedRtt = this.smoothedRtt === null ? rtt : this.smoothedRtt + (rtt - this.smoothedRtt) / 8;
    let best = this.samples[0];
    // A steady server's anchors lie within one tick of each other; an older sample more than PHASE_SPREAD_TICKS before
    // the newest one is from before the server fell behind (a stall, a slowed room) and no longer says its phase.
    const newest = this.samples[this.samples.length - 1].anchorMs;
    let anchor = newest;
    for (const s of this.samples) {
      if (s.rttMs < best.rttMs) best = s;
      if (s.anchorMs < anchor && s.anchorMs > newest - PHASE_SPREAD_TICKS * this.tickMs) anchor = s.anchorMs;
    }
    this.originLocalMs = anchor - best.offsetMs;
    return true;
  }

  /** Whether any estimate exists (welcome or pong). */
  get ready(): boolean {
    return this.originLocalMs !== null;
  }

  /** Pong samples in the window. */
  get sampleCount(): number {
    return this.samples.length;
  }

  /** Samples refused (negative RTT, non-finite values). */
  get rejectedSamples(): number {
    return this.rejected;
  }

  /** Smoothed round-trip time (ms), null before the first pong. */
  get rttMs(): number | null {
    return this.smoothedRtt;
  }

  /** Lowest RTT in the window (ms), null before the first pong. */
  get minRttMs(): number | null {
    if (this.samples.length === 0) return null;
    let m = Infinity;
    for (const s of this.samples) m = Math.min(m, s.rttMs);
    return m;
  }

  /** RTT variation: mean of (RTT − lowest RTT) over the window (ms); 0 before two samples. */
  get jitterMs(): number {
    const min = this.minRttMs;
    if (min === null || this.samples.length < 2) return 0;
    let sum = 0;
    for (const s of this.samples) sum += s.rttMs - min;
    return sum / this.samples.length;
  }

  /** Server clock minus local clock (ms), from the lowest-RTT sample; null before the first pong. */
  get offsetMs(): number | null {
    if (this.samples.length === 0) return null;
    let best = this.samples[0];
    for (const s of this.samples) if (s.rttMs < best.rttMs) best = s;
    return best.offsetMs;
  }

  /** The server's tick count (fractional) at a local time; throws before seed() or the first pong. */
  serverTickAt(localMs: number): number {
    if (this.originLocalMs === null) throw new Error('ClockSync: no estimate yet (no welcome or pong)');
    return (localMs - this.originLocalMs) / this.tickMs;
  }

  /** The local time at which the server's tick count reaches `tick`. */
  localTimeOfTick(tick: number): number {
    if (this.originLocalMs === null) throw new Error('ClockSync: no estimate yet (no welcome or pong)');
    return this.originLocalMs + tick * this.tickMs;
  }

  /** Forgets everything (a new connection). */
  reset(): void {
    this.samples = [];
    this.smoothedRtt = null;
    this.originLocalMs = null;
  }
}
