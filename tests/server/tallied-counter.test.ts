// Tests for server/tallied-counter.ts: increments summed in place show up in every scrape exactly as prom-client's own
// counter would show them, per label value; bad values and unknown labels are still refused.
import { Registry } from 'prom-client';
import { describe, expect, it } from 'vitest';
import { talliedCounter } from '../../server/tallied-counter.ts';

describe('talliedCounter', () => {
  it('shows the sum of every increment at each scrape, and keeps counting after it', async () => {
    const registry = new Registry();
    const bytes = talliedCounter({ name: 't_bytes_total', help: 'bytes', registers: [registry] });
    bytes.inc(100);
    bytes.inc();
    bytes.inc(0.5);
    expect(await registry.getSingleMetricAsString('t_bytes_total')).toMatch(/^t_bytes_total 101\.5$/m);
    bytes.inc(10);
    expect(await registry.getSingleMetricAsString('t_bytes_total')).toMatch(/^t_bytes_total 111\.5$/m);
    expect((await bytes.get()).values).toEqual([{ value: 111.5, labels: {} }]);
  });

  it('sums per label value, and resets', async () => {
    const registry = new Registry();
    const sent = talliedCounter({ name: 't_sent_total', help: 'sent', labelNames: ['kind'], registers: [registry] });
    sent.inc({ kind: 'delta' });
    sent.inc({ kind: 'full' });
    sent.inc({ kind: 'delta' }, 2);
    const text = await registry.getSingleMetricAsString('t_sent_total');
    expect(text).toMatch(/^t_sent_total\{kind="delta"\} 3$/m);
    expect(text).toMatch(/^t_sent_total\{kind="full"\} 1$/m);
    sent.inc({ kind: 'full' });
    sent.reset();
    expect(await registry.getSingleMetricAsString('t_sent_total')).not.toMatch(/kind=/);
  });

  it('refuses negative and non-finite values and labels it does not have, as prom-client does', () => {
    const registry = new Registry();
    const plain = talliedCounter({ name: 't_plain_total', help: 'plain', registers: [registry] });
    const labelled = talliedCounter({ name: 't_labelled_total', help: 'labelled', labelNames: ['reason'], registers: [registry] });
    expect(() => plain.inc(-1)).toThrow(/decrease/);
    expect(() => plain.inc(Number.POSITIVE_INFINITY)).toThrow(/not a valid number/);
    expect(() => labelled.inc({ kind: 'x' })).toThrow(/label/i);
    expect(() => labelled.inc({ reason: 'a', kind: 'x' })).toThrow(/label/i);
    expect(() => talliedCounter({ name: 't_two', help: 'two', labelNames: ['a', 'b'], registers: [registry] })).toThrow(/at most one label/);
  });
});
