// A prom-client Counter for the per-message and per-member hot path: inc() only adds to plain numbers (one per label
// value; at most one label), and the sums reach prom-client when it collects (every scrape and every get()). Counting
// then costs an addition instead of prom-client's label hashing, checks and allocations. Anything unusual (a bad
// value, other labels) goes to prom-client's own inc, which checks and throws as before.
import { Counter, type Registry } from 'prom-client';

/** Options of talliedCounter: prom-client's, with at most one label name. */
export interface TalliedCounterConfig {
  name: string;
  help: string;
  labelNames?: string[];
  registers: Registry[];
}

type Labels = Partial<Record<string, string | number>>;

/** A Counter whose plain increments are summed in place until prom-client collects. */
export function talliedCounter(config: TalliedCounterConfig): Counter<string> {
  const labelNames = config.labelNames ?? [];
  if (labelNames.length > 1) throw new Error(`talliedCounter ${config.name}: at most one label, got ${labelNames.join(', ')}`);
  const label = labelNames[0];
  let pending = 0;
  const pendingByValue = new Map<string, number>();
  const counter: Counter<string> = new Counter({ name: config.name, help: config.help, labelNames, registers: config.registers, collect: () => flush() });
  const promInc = counter.inc.bind(counter) as (labels?: Labels | number, value?: number) => void;
  const promReset = counter.reset.bind(counter);
  const flush = (): void => {
    if (pending > 0) promInc(pending);
    pending = 0;
    for (const [value, n] of pendingByValue) promInc({ [label!]: value }, n);
    pendingByValue.clear();
  };
  const plain = (n: number): boolean => Number.isFinite(n) && n >= 0;
  counter.inc = ((labelsOrValue?: Labels | number, value?: number): void => {
    if (labelsOrValue === undefined || typeof labelsOrValue === 'number') {
      const n = labelsOrValue ?? 1;
      if (label === undefined && plain(n)) pending += n;
      else promInc(labelsOrValue, value);
      return;
    }
    const n = value ?? 1;
    const labelValue = label === undefined ? undefined : labelsOrValue[label];
    if (labelValue === undefined || !plain(n) || !onlyKey(labelsOrValue, label!)) {
      promInc(labelsOrValue, value);
      return;
    }
    const key = String(labelValue);
    pendingByValue.set(key, (pendingByValue.get(key) ?? 0) + n);
  }) as Counter<string>['inc'];
  counter.reset = (): void => {
    pending = 0;
    pendingByValue.clear();
    promReset();
  };
  return counter;
}

function onlyKey(labels: Labels, key: string): boolean {
  let n = 0;
  for (const k in labels) if (k !== key || ++n > 1) return false;
  return n === 1;
}
