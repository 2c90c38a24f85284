// Tests of the process's heap growth setting: whole percents in range are taken, anything else is refused before V8
// sees it (a bad flag string would be ignored by V8 without a word).
import { describe, expect, it } from 'vitest';
import { DEFAULT_HEAP_GROWING_PERCENT, setHeapGrowingPercent } from '../../server/heap-growth.ts';

describe('heap-growth', () => {
  it('takes whole percents from 0 (V8 decides) to 1000', () => {
    expect(() => setHeapGrowingPercent(0)).not.toThrow();
    expect(() => setHeapGrowingPercent(DEFAULT_HEAP_GROWING_PERCENT)).not.toThrow();
  });

  it('refuses fractions, negatives and absurd growth', () => {
    for (const bad of [-1, 2.5, 1001, Number.NaN]) expect(() => setHeapGrowingPercent(bad)).toThrow(/heap growing percent/);
  });
});
