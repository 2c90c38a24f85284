// Sample statistics for the benchmarks: median, percentiles (linear interpolation between order statistics),
// mean, ratios of two sample sets, and the alternating-batch driver that lets machine noise hit both sides alike.

/** A summary of one sample set (milliseconds unless said otherwise). */
export interface Summary {
  count: number;
  mean: number;
  median: number;
  p90: number;
  p99: number;
  min: number;
  max: number;
}

function checkSamples(samples: readonly number[], what: string): void {
  if (!Array.isArray(samples) || samples.length === 0) throw new Error(`${what}: needs at least one sample`);
  for (const v of samples) if (typeof v !== 'number' || !Number.isFinite(v)) throw new Error(`${what}: samples must be finite numbers, got ${String(v)}`);
}

function sorted(samples: readonly number[]): number[] {
  return [...samples].sort((a, b) => a - b);
}

function quantileSorted(s: readonly number[], q: number): number {
  const pos = (s.length - 1) * q;
  const lo = Math.floor(pos);
  const hi = Math.ceil(pos);
  return s[lo] + (s[hi] - s[lo]) * (pos - lo);
}

/** The q-quantile (q in [0, 1]), interpolating linearly between the two nearest order statistics. */
export function quantile(samples: readonly number[], q: number): number {
  checkSamples(samples, 'quantile');
  if (!(q >= 0 && q <= 1)) throw new Error(`quantile: q must be in [0, 1], got ${q}`);
  return quantileSorted(sorted(samples), q);
}

/** The median (mean of the middle two for an even count). */
export function median(samples: readonly number[]): number {
  return quantile(samples, 0.5);
}

/** The arithmetic mean. */
export function mean(samples: readonly number[]): number {
  checkSamples(samples, 'mean');
  let sum = 0;
  for (const v of samples) sum += v;
  return sum / samples.length;
}

/** The sum. */
export function sum(samples: readonly number[]): number {
  let total = 0;
  for (const v of samples) total += v;
  return total;
}

/** Count, mean, median, p90, p99, min and max of a sample set. */
export function summarize(samples: readonly number[]): Summary {
  checkSamples(samples, 'summarize');
  const s = sorted(samples);
  return {
    count: s.length,
    mean: mean(s),
    median: quantileSorted(s, 0.5),
    p90: quantileSorted(s, 0.9),
    p99: quantileSorted(s, 0.99),
    min: s[0],
    max: s[s.length - 1],
  };
}

/** a / b, or null when b is not a positive number (a ratio against nothing is no figure). */
export function ratio(a: number, b: number): number | null {
  if (!Number.isFinite(a) || !Number.isFinite(b) || b <= 0) return null;
  return a / b;
}

/** Rounds to `digits` decimals (for results files: no float noise like 1.0999999). */
export function round(value: number, digits: number): number {
  if (!Number.isFinite(value)) return value;
  const f = 10 ** digits;
  return Math.round(value * f) / f;
}

/** Rounds every number in a Summary. */
export function roundSummary(s: Summary, digits = 4): Summary {
  return {
    count: s.count,
    mean: round(s.mean, digits),
    median: round(s.median, digits),
    p90: round(s.p90, digits),
    p99: round(s.p99, digits),
    min: round(s.min, digits),
    max: round(s.max, digits),
  };
}

/**
 * Runs `batches` rounds of A and B, swapping which goes first every round (A B, B A, A B, …) so drifts in machine
 * load and warm-up hit both sides alike. Each side gets the round index.
 */
export async function alternate(batches: number, runA: (round: number) => Promise<void> | void, runB: (round: number) => Promise<void> | void): Promise<void> {
  if (!Number.isInteger(batches) || batches < 1) throw new Error(`alternate: batches must be a positive integer, got ${batches}`);
  for (let i = 0; i < batches; i++) {
    if (i % 2 === 0) {
      await runA(i);
      await runB(i);
    } else {
      await runB(i);
      await runA(i);
    }
  }
}

/** Milliseconds spent in `fn` (performance.now, sub-microsecond resolution in Node). */
export function timeMs(fn: () => void): number {
  const t0 = performance.now();
  fn();
  return performance.now() - t0;
}

/** A straight line through points: y ≈ intercept + slope · x, with the share of variance it explains (r²). */
export interface LinearFit {
  slope: number;
  intercept: number;
  r2: number;
  points: number;
}

/** Ordinary least squares of ys on xs (at least two distinct xs). */
export function linearFit(xs: readonly number[], ys: readonly number[]): LinearFit {
  checkSamples(xs, 'linearFit');
  checkSamples(ys, 'linearFit');
  if (xs.length !== ys.length) throw new Error(`linearFit: ${xs.length} xs but ${ys.length} ys`);
  const mx = mean(xs);
  const my = mean(ys);
  let sxx = 0;
  let sxy = 0;
  let syy = 0;
  for (let i = 0; i < xs.length; i++) {
    sxx += (xs[i] - mx) * (xs[i] - mx);
    sxy += (xs[i] - mx) * (ys[i] - my);
    syy += (ys[i] - my) * (ys[i] - my);
  }
  if (sxx === 0) throw new Error('linearFit: needs at least two distinct x values');
  const slope = sxy / sxx;
  return { slope, intercept: my - slope * mx, r2: syy === 0 ? 1 : (sxy * sxy) / (sxx * syy), points: xs.length };
}
