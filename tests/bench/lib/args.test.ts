// Tests for the bench's command line: the documented flags, repeatable --only, --out, and refusals of typos.
import { describe, expect, it } from 'vitest';
import { benchUsage, parseBenchArgs } from '../../../bench/lib/args.ts';

const FIGURES = ['tick-overhead', 'bandwidth', 'engine-peer'];
const parse = (...argv: string[]) => parseBenchArgs(argv, FIGURES);

describe('args', () => {
  it('runs everything, fully, without flags', () => {
    expect(parse()).toEqual({ quick: false, json: false, peers: false, only: [], outDir: null, help: false });
  });

  it('reads --quick --json --peers together (npm run bench -- --quick --json)', () => {
    expect(parse('--quick', '--json', '--peers')).toMatchObject({ quick: true, json: true, peers: true });
  });

  it('collects repeated --only names once each, in both value forms', () => {
    expect(parse('--only', 'bandwidth', '--only=tick-overhead', '--only', 'bandwidth').only).toEqual(['bandwidth', 'tick-overhead']);
  });

  it('takes --out DIR', () => {
    expect(parse('--out', '/tmp/x').outDir).toBe('/tmp/x');
  });

  it('refuses an unknown figure and names the known ones', () => {
    expect(() => parse('--only', 'bandwith')).toThrow(/unknown figure "bandwith" \(figures: tick-overhead, bandwidth, engine-peer\)/);
  });

  it('refuses unknown flags and flags missing their value', () => {
    expect(() => parse('--quik')).toThrow(/unknown argument "--quik"/);
    expect(() => parse('--only')).toThrow(/--only needs a value/);
    expect(() => parse('--out', '--quick')).toThrow(/--out needs a value/);
  });

  it('lists every figure in the usage text', () => {
    const text = benchUsage(FIGURES);
    for (const f of FIGURES) expect(text).toContain(f);
    expect(text).toContain('--quick');
  });
});
