// Tests for the hand-written SVG charts: one bar per value with lengths in proportion, n/a for missing values, a
// dashed goal line, escaped labels, log axes by powers of ten, and short value labels.
import { describe, expect, it } from 'vitest';
import type { Chart } from '../../../bench/lib/figure.ts';
import { escapeXml, formatValue, renderChartSvg, SERIES_COLORS } from '../../../bench/lib/svg.ts';

const widths = (svg: string): number[] => [...svg.matchAll(/<rect x="[\d.]+" y="[\d.]+" width="([\d.]+)"/g)].map((m) => Number(m[1]));

describe('svg', () => {
  const chart: Chart = {
    title: 'Tick <overhead> & more',
    unit: 'ms',
    goal: 1.1,
    bars: [
      { label: 'raw', value: 1, series: 'raw' },
      { label: 'full', value: 2, series: 'ours' },
      { label: 'missing', value: null, series: 'baseline' },
    ],
  };

  it('renders a standalone SVG document whose height fits the bars', () => {
    const svg = renderChartSvg(chart);
    expect(svg.startsWith('<svg xmlns="http://www.w3.org/2000/svg"')).toBe(true);
    expect(svg.trimEnd().endsWith('</svg>')).toBe(true);
    const height = Number(svg.match(/height="(\d+)"/)![1]);
    const more = renderChartSvg({ ...chart, bars: [...chart.bars, { label: 'x', value: 1, series: 'other' }] });
    expect(Number(more.match(/height="(\d+)"/)![1])).toBeGreaterThan(height);
  });

  it('draws bars in proportion to their values on a linear axis', () => {
    const [raw, full] = widths(renderChartSvg(chart));
    expect(full / raw).toBeCloseTo(2, 1);
  });

  it('colours bars by series and writes n/a for a missing value', () => {
    const svg = renderChartSvg(chart);
    expect(svg).toContain(`fill="${SERIES_COLORS.raw}"`);
    expect(svg).toContain(`fill="${SERIES_COLORS.ours}"`);
    expect(svg).not.toContain(`fill="${SERIES_COLORS.baseline}"`);
    expect(svg).toContain('>n/a<');
  });

  it('draws the goal as a dashed line with its value', () => {
    const svg = renderChartSvg(chart);
    expect(svg).toMatch(/stroke-dasharray="4 3"/);
    expect(svg).toContain('goal 1.1<');
    expect(renderChartSvg({ ...chart, goal: undefined })).not.toContain('stroke-dasharray');
  });

  it('escapes markup in titles and labels', () => {
    const svg = renderChartSvg(chart);
    expect(svg).toContain('Tick &lt;overhead&gt; &amp; more');
    expect(escapeXml('"a" <b>')).toBe('&quot;a&quot; &lt;b&gt;');
  });

  it('spaces a log axis by powers of ten so bars a thousandfold apart both show', () => {
    const svg = renderChartSvg({ title: 't', unit: 'kbps', log: true, bars: [{ label: 'ours', value: 70, series: 'ours' }, { label: 'naive', value: 10000, series: 'baseline' }] });
    for (const tick of ['>10<', '>100<', '>1000<', '>10k<']) expect(svg).toContain(tick);
    const [ours, naive] = widths(svg);
    expect(ours).toBeGreaterThan(50);
    expect(naive).toBeGreaterThan(ours);
  });

  it('labels values with about three significant digits', () => {
    expect(formatValue(0)).toBe('0');
    expect(formatValue(0.01234)).toBe('0.012');
    expect(formatValue(1.234)).toBe('1.23');
    expect(formatValue(12.34)).toBe('12.3');
    expect(formatValue(123.4)).toBe('123');
    expect(formatValue(1.5)).toBe('1.5');
    expect(formatValue(10)).toBe('10');
    expect(formatValue(12345)).toBe('12.3k');
    expect(formatValue(123456)).toBe('123k');
  });
});
