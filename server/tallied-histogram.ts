// A prom-client Histogram for the tick path: a plain observe(value) (no labels) only stores the value, and the stored
// values reach prom-client's own observe, in order, when it collects (every scrape and every get()) or when the store
// is full. Scrapes show exactly what observing at once would have; the tick pays a store instead of prom-client's
// label handling, closure and bucket search (after the physics step, with cold caches, several µs a call). Anything
// else (labels, a non-finite value) goes to prom-client's observe at once, which checks and throws as before.
import { Histogram, type Registry } from 'prom-client';

/** Values held before they are handed to prom-client in one go (4 KiB; a minute of one room's ticks is 3600). */
export const TALLY_CAPACITY = 512;

/** Options of talliedHistogram: prom-client's, without labels. */
export interface TalliedHistogramConfig {
  name: string;
  help: string;
  buckets: number[];
  registers: Registry[];
}

/** An unlabelled Histogram whose observations are stored in place until prom-client collects. */
export function talliedHistogram(config: TalliedHistogramConfig): Histogram<string> {
  const pending = new Float64Array(TALLY_CAPACITY);
  let count = 0;
  const histogram: Histogram<string> = new Histogram({ name: config.name, help: config.help, buckets: config.buckets, registers: config.registers, collect: () => flush() });
  const promObserve = histogram.observe.bind(histogram) as (labelsOrValue?: unknown, value?: number) => void;
  const promReset = histogram.reset.bind(histogram);
  const flush = (): void => {
    const n = count;
    count = 0; // first: a throwing observe must not leave values to be observed twice
    for (let i = 0; i < n; i++) promObserve(pending[i]);
  };
  histogram.observe = ((labelsOrValue?: unknown, value?: number): void => {
    if (typeof labelsOrValue === 'number' && value === undefined && Number.isFinite(labelsOrValue)) {
      pending[count++] = labelsOrValue;
      if (count === TALLY_CAPACITY) flush();
      return;
    }
    flush();
    promObserve(labelsOrValue, value);
  }) as Histogram<string>['observe'];
  histogram.reset = (): void => {
    count = 0;
    promReset();
  };
  return histogram;
}
