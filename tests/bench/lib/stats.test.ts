// Tests for the bench's sample statistics: quantiles by linear interpolation, summaries, ratios, rounding, and the
// alternating A/B batch order that spreads machine noise over both sides.
import { describe, expect, it } from 'vitest';
import { alternate, linearFit, mean, median, quantile, ratio, round, summarize, sum } from '../../../bench/lib/stats.ts';

describe('stats', () => {
  it('takes the middle value as the median of an odd count and the mean of the middle two of an even count', () => {
    expect(median([5, 1, 3])).toBe(3);
    expect(median([4, 1, 3, 2])).toBe(2.5);
  });

  it('interpolates quantiles between neighbouring order statistics', () => {
    const samples = Array.from({ length: 101 }, (_, i) => i); // 0…100
    expect(quantile(samples, 0.99)).toBeCloseTo(99, 10);
    expect(quantile([0, 10], 0.25)).toBeCloseTo(2.5, 10);
    expect(quantile([7], 0.99)).toBe(7);
  });

  it('does not reorder the caller’s samples', () => {
    const samples = [3, 1, 2];
    median(samples);
    expect(samples).toEqual([3, 1, 2]);
  });

  it('summarizes count, mean, median, p90, p99, min and max', () => {
    const s = summarize([2, 4, 6, 8, 100]);
    expect(s).toMatchObject({ count: 5, mean: 24, median: 6, min: 2, max: 100 });
    expect(s.p99).toBeGreaterThan(s.p90);
    expect(s.p99).toBeLessThanOrEqual(100);
    expect(sum([1, 2, 3.5])).toBe(6.5);
    expect(mean([1, 2])).toBe(1.5);
  });

  it('refuses empty and non-finite samples with a clear error', () => {
    expect(() => median([])).toThrow(/at least one sample/);
    expect(() => summarize([1, Number.NaN])).toThrow(/finite numbers/);
    expect(() => quantile([1, 2], 1.5)).toThrow(/q must be in \[0, 1\]/);
  });

  it('gives no ratio against zero or a non-number', () => {
    expect(ratio(3, 2)).toBe(1.5);
    expect(ratio(3, 0)).toBeNull();
    expect(ratio(Number.NaN, 2)).toBeNull();
  });

  it('rounds to the given decimals without float noise', () => {
    expect(round(1.0999999999, 3)).toBe(1.1);
    expect(round(2.345, 1)).toBe(2.3);
  });

  it('alternates which side runs first in each round', async () => {
    const order: string[] = [];
    await alternate(
      4,
      (i) => void order.push(`A${i}`),
      (i) => void order.push(`B${i}`),
    );
    expect(order).toEqual(['A0', 'B0', 'B1', 'A1', 'A2', 'B2', 'B3', 'A3']);
  });

  it('awaits asynchronous sides in order', async () => {
    const order: string[] = [];
    await alternate(
      2,
      async (i) => {
        await new Promise((r) => setTimeout(r, 5));
        order.push(`A${i}`);
      },
      (i) => void order.push(`B${i}`),
    );
    expect(order).toEqual(['A0', 'B0', 'B1', 'A1']);
  });
  it('fits a least-squares line and says how much of the variance it explains', () => {
    const exact = linearFit([1, 16, 64], [0.5 + 0.01, 0.5 + 0.16, 0.5 + 0.64]);
    expect(exact.slope).toBeCloseTo(0.01, 12);
    expect(exact.intercept).toBeCloseTo(0.5, 12);
    expect(exact.r2).toBeCloseTo(1, 12);
    const noisy = linearFit([0, 1, 2, 3], [0, 2, 1, 3]);
    expect(noisy.slope).toBeCloseTo(0.8, 12);
    expect(noisy.r2).toBeLessThan(1);
  });

  it('refuses a line through a single x value or mismatched lists', () => {
    expect(() => linearFit([2, 2], [1, 3])).toThrow(/two distinct x/);
    expect(() => linearFit([1, 2], [1])).toThrow(/2 xs but 1 ys/);
  });
});
