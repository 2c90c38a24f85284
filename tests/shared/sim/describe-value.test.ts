// Tests of describeValue: numbers, strings and bigints are shown as written (−0 included), everything else by kind,
// and no code of the described value ever runs (conversion keys, getters, Proxy traps), whatever it is.
import { describe, expect, it } from 'vitest';
import { describeValue } from '../../../shared/sim/describe-value.ts';
import { Prng } from '../../../shared/sim/prng.ts';
import { hostileValue, touched } from '../../helpers/hostile-values.ts';

describe('describeValue', () => {
  it('shows numbers with −0, NaN and the infinities as written', () => {
    expect([0, -0, 1.5, Number.NaN, Number.POSITIVE_INFINITY, Number.NEGATIVE_INFINITY, 2 ** 53].map(describeValue)).toEqual(['0', '-0', '1.5', 'NaN', 'Infinity', '-Infinity', '9007199254740992']);
  });

  it('quotes strings, escapes control characters and cuts long ones', () => {
    expect(describeValue('Ada')).toBe('"Ada"');
    expect(describeValue('a"\u0000\n')).toBe('"a\\"\\u0000\\n"');
    expect(describeValue('x'.repeat(100))).toBe(`"${'x'.repeat(40)}…" (100 characters)`);
  });

  it('shows small bigints and only the size of huge ones', () => {
    expect(describeValue(5n)).toBe('5n');
    expect(describeValue(-(2n ** 70n))).toBe('a bigint of -72 bits');
  });

  it('names everything else by kind', () => {
    expect([null, undefined, true, [1], new Uint8Array(3), new Float32Array(1), {}, () => 1, Symbol('s')].map(describeValue)).toEqual([
      'null',
      'undefined',
      'true',
      'an array',
      'binary (3 bytes)',
      'a typed array',
      'an object',
      'a function',
      'a symbol',
    ]);
  });

  it('runs no code of the value and never throws, for any of 20,000 hostile values', () => {
    const rng = new Prng(20240);
    const before = touched.count;
    const odd: string[] = [];
    for (let i = 0; i < 20_000; i++) {
      const text = describeValue(hostileValue(rng, 2));
      if (typeof text !== 'string' || text.length > 70 || text.includes('[object')) odd.push(String(text));
    }
    expect(odd).toEqual([]);
    expect(touched.count).toBe(before);
  });
});
