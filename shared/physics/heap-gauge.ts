// A cheap stand-in for Jolt's free-heap query on the hot path (issue 14, item 3). sGetFreeMemory walks the WASM
// allocator (mallinfo) on every call, which showed at 1.6–3.2% of a bullet-heavy tick. The gauge keeps the last exact
// reading of one module's heap and subtracts every estimate it has let through since; it asks the heap again every
// REFRESH_EVERY grants, whenever its estimate comes within SLACK_BYTES of the reserve, and after every exact reading
// anyone makes. Near a full heap every check is therefore exact, so a full heap still raises a clear Error.
import type { JoltModule } from './jolt-backend.ts';

/** Grants between two exact readings (an estimate drifts by at most this many estimates' error). */
export const REFRESH_EVERY = 64;
/** How close to the reserve an estimate may come before the gauge asks the heap itself. */
export const SLACK_BYTES = 4 * 1024 * 1024;

/** The free-heap gauge of one Jolt module, shared by every world built on it. */
export class HeapGauge {
  private readonly J: JoltModule;
  private lastFreeBytes = 0;
  private grantedBytes = 0;
  private grantsSinceRead = REFRESH_EVERY; // the first check reads the heap
  /** Exact heap readings taken so far (for tests and benches). */
  exactReads = 0;

  constructor(J: JoltModule) {
    this.J = J;
  }

  /** The exact free bytes of the module's heap; resets the estimate. */
  read(): number {
    this.exactReads++;
    this.lastFreeBytes = this.J.JoltInterface.prototype.sGetFreeMemory();
    this.grantedBytes = 0;
    this.grantsSinceRead = 0;
    return this.lastFreeBytes;
  }

  /**
   * Free bytes to judge a request for `bytes` against, keeping `minFreeBytes` in reserve: the estimate when it is
   * comfortably clear of the reserve and fresh enough, else an exact reading.
   */
  freeBytesFor(bytes: number, minFreeBytes: number): number {
    const estimate = this.lastFreeBytes - this.grantedBytes;
    if (this.grantsSinceRead < REFRESH_EVERY && estimate - bytes >= minFreeBytes + SLACK_BYTES) return estimate;
    return this.read();
  }

  /** Records that `bytes` were let through (they are counted as gone until the next exact reading). */
  grant(bytes: number): void {
    this.grantedBytes += bytes;
    this.grantsSinceRead++;
  }
}

const gauges = new WeakMap<JoltModule, HeapGauge>();

/** The gauge of a module (one per module, so worlds sharing a heap see each other's grants). */
export function heapGaugeOf(J: JoltModule): HeapGauge {
  let g = gauges.get(J);
  if (!g) {
    g = new HeapGauge(J);
    gauges.set(J, g);
  }
  return g;
}
