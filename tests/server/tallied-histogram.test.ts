// Tests for server/tallied-histogram.ts: observations stored in place show up in every scrape exactly as prom-client's
// own histogram shows them (buckets, sum, count), also past the store's capacity; bad values are still refused.
import { Histogram, Registry } from 'prom-client';
import { describe, expect, it } from 'vitest';
import { TALLY_CAPACITY, talliedHistogram } from '../../server/tallied-histogram.ts';

const BUCKETS = [0.001, 0.004, 0.016, 0.1];

/** The same observations through a tallied histogram and a plain prom-client one, as scraped text. */
async function bothScrapes(values: readonly number[], scrapeEvery = Infinity): Promise<[string, string]> {
  const registry = new Registry();
  const tallied = talliedHistogram({ name: 't_tick_seconds', help: 'tick', buckets: BUCKETS, registers: [registry] });
  const plain = new Histogram({ name: 'p_tick_seconds', help: 'tick', buckets: BUCKETS, registers: [registry] });
  for (let i = 0; i < values.length; i++) {
    tallied.observe(values[i]);
    plain.observe(values[i]);
    if ((i + 1) % scrapeEvery === 0) await registry.metrics();
  }
  const t = await registry.getSingleMetricAsString('t_tick_seconds');
  const p = await registry.getSingleMetricAsString('p_tick_seconds');
  return [t.replaceAll('t_tick_seconds', 'x'), p.replaceAll('p_tick_seconds', 'x')];
}

describe('talliedHistogram', () => {
  it('scrapes the same buckets, sum and count as prom-client observing at once', async () => {
    const values = Array.from({ length: 37 }, (_, i) => ((i * 7919) % 113) / 1000);
    const [tallied, plain] = await bothScrapes(values);
    expect(tallied).toBe(plain);
    expect(tallied).toMatch(/^x_count 37$/m);
  });

  it('stays exact across scrapes and past its store capacity', async () => {
    const values = Array.from({ length: TALLY_CAPACITY * 2 + 5 }, (_, i) => ((i * 104729) % 997) / 5000);
    const [tallied, plain] = await bothScrapes(values, 300);
    expect(tallied).toBe(plain);
    expect(tallied).toMatch(new RegExp(`^x_count ${values.length}$`, 'm'));
  });

  it('shows stored values in get(), forgets them on reset, and refuses non-finite values', async () => {
    const registry = new Registry();
    const h = talliedHistogram({ name: 't_step_seconds', help: 'step', buckets: BUCKETS, registers: [registry] });
    h.observe(0.002);
    h.observe(0.05);
    const count = (await h.get()).values.find((v) => v.metricName === 't_step_seconds_count');
    expect(count?.value).toBe(2);
    h.observe(0.003);
    h.reset();
    expect(await registry.getSingleMetricAsString('t_step_seconds')).not.toMatch(/^t_step_seconds_count [1-9]/m);
    h.observe(0.003);
    expect(await registry.getSingleMetricAsString('t_step_seconds')).toMatch(/^t_step_seconds_count 1$/m);
    expect(() => h.observe(Number.NaN)).toThrow(/not a valid number/);
  });
});
