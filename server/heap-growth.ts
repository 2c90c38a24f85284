// How far V8 lets the old generation grow past what a full collection left alive, for the whole process (main thread
// and room workers: V8's flags are per process and read whenever a heap sets its next limit). V8 sizes that headroom by
// throughput: a room server's thread is mostly idle, so it allows ~10–40%, and once the headroom is smaller than the
// young generation every young-generation fill becomes a full mark-compact (measured: one a second with 8 rooms on a
// thread, each 100 ms of marking that stalls every room of the thread). Fixed headroom keeps young fills to scavenges.
import { setFlagsFromString } from 'node:v8';

/** Old-generation growth past the live size after a full collection, in percent, unless the server is told otherwise. */
export const DEFAULT_HEAP_GROWING_PERCENT = 100;

let applied: number | null = null;

/** Sets V8's heap growing factor to 1 + percent/100 for this process (0 gives V8 back its own rule). Idempotent. */
export function setHeapGrowingPercent(percent: number): void {
  if (!Number.isInteger(percent) || percent < 0 || percent > 1000) throw new Error(`heap growing percent must be a whole number in [0, 1000], got ${percent}`);
  if (applied === percent) return;
  setFlagsFromString(`--heap-growing-percent=${percent}`);
  applied = percent;
}
