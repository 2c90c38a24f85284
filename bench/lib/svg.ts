// Hand-written SVG for the results page: one small horizontal bar chart per figure (linear or log axis, an optional
// dashed goal line, colours by series). No chart library; the output is deterministic text for review diffs.
import type { Chart, ChartBar } from './figure.ts';

const WIDTH = 720;
const LABEL_WIDTH = 290;
const VALUE_WIDTH = 90;
const BAR_HEIGHT = 18;
const BAR_GAP = 6;
const TOP = 44;
const BOTTOM = 30;
const PLOT_WIDTH = WIDTH - LABEL_WIDTH - VALUE_WIDTH - 10;

/** Fill colour of each series. */
export const SERIES_COLORS: Readonly<Record<ChartBar['series'], string>> = Object.freeze({
  ours: '#2f7ed8',
  baseline: '#b0b0b0',
  raw: '#3aa655',
  other: '#e0a030',
});

/** Escapes text for SVG content and attributes. */
export function escapeXml(text: string): string {
  return text.replace(/&/g, '&amp;').replace(/</g, '&lt;').replace(/>/g, '&gt;').replace(/"/g, '&quot;');
}

/** A number as a short label: about 3 significant digits, no trailing zeros, thousands as "12.3k". */
export function formatValue(value: number): string {
  const trim = (text: string): string => (text.includes('.') ? text.replace(/\.?0+$/, '') : text);
  const a = Math.abs(value);
  if (a >= 100000) return `${(value / 1000).toFixed(0)}k`;
  if (a >= 10000) return `${trim((value / 1000).toFixed(1))}k`;
  if (a >= 100) return value.toFixed(0);
  if (a >= 10) return trim(value.toFixed(1));
  if (a >= 1) return trim(value.toFixed(2));
  if (a === 0) return '0';
  return trim(value.toPrecision(2));
}

interface Axis {
  toX(value: number): number;
  ticks: number[];
}

function niceStep(range: number): number {
  const raw = range / 4;
  const mag = 10 ** Math.floor(Math.log10(raw));
  const n = raw / mag;
  return (n <= 1 ? 1 : n <= 2 ? 2 : n <= 5 ? 5 : 10) * mag;
}

function linearAxis(maxValue: number): Axis {
  const max = maxValue > 0 ? maxValue : 1;
  const step = niceStep(max);
  const top = Math.ceil(max / step) * step;
  const ticks: number[] = [];
  for (let v = 0; v <= top + step / 2; v += step) ticks.push(v);
  return { toX: (v) => LABEL_WIDTH + (Math.max(0, v) / top) * PLOT_WIDTH, ticks };
}

function logAxis(minValue: number, maxValue: number): Axis {
  const lo = Math.floor(Math.log10(minValue > 0 ? minValue : 1));
  const hi = Math.max(lo + 1, Math.ceil(Math.log10(maxValue > 0 ? maxValue : 10)));
  const ticks: number[] = [];
  for (let e = lo; e <= hi; e++) ticks.push(10 ** e);
  const toX = (v: number): number => {
    const e = Math.log10(Math.max(v, 10 ** lo));
    return LABEL_WIDTH + ((e - lo) / (hi - lo)) * PLOT_WIDTH;
  };
  return { toX, ticks };
}

/** Renders a chart as a standalone SVG document. Bars without a value are drawn as "n/a". */
export function renderChartSvg(chart: Chart): string {
  const values = chart.bars.map((b) => b.value).filter((v): v is number => v !== null && Number.isFinite(v));
  if (chart.goal !== undefined) values.push(chart.goal);
  const positive = values.filter((v) => v > 0);
  const axis = chart.log ? logAxis(positive.length > 0 ? Math.min(...positive) : 1, positive.length > 0 ? Math.max(...positive) : 10) : linearAxis(values.length > 0 ? Math.max(...values) : 1);
  const height = TOP + chart.bars.length * (BAR_HEIGHT + BAR_GAP) + BOTTOM;
  const plotBottom = height - BOTTOM + 4;
  const out: string[] = [];
  out.push(`<svg xmlns="http://www.w3.org/2000/svg" width="${WIDTH}" height="${height}" viewBox="0 0 ${WIDTH} ${height}" font-family="sans-serif" font-size="12">`);
  out.push(`<rect width="${WIDTH}" height="${height}" fill="#ffffff"/>`);
  out.push(`<text x="8" y="18" font-size="14" font-weight="bold">${escapeXml(chart.title)}</text>`);
  for (const t of axis.ticks) {
    const x = axis.toX(t).toFixed(1);
    out.push(`<line x1="${x}" y1="${TOP - 6}" x2="${x}" y2="${plotBottom}" stroke="#e6e6e6"/>`);
    out.push(`<text x="${x}" y="${plotBottom + 14}" text-anchor="middle" fill="#666">${escapeXml(formatValue(t))}</text>`);
  }
  out.push(`<text x="${WIDTH - 8}" y="${plotBottom + 14}" text-anchor="end" fill="#666">${escapeXml(chart.unit)}</text>`);
  chart.bars.forEach((bar, i) => {
    const y = TOP + i * (BAR_HEIGHT + BAR_GAP);
    const mid = (y + BAR_HEIGHT / 2 + 4).toFixed(1);
    out.push(`<text x="${LABEL_WIDTH - 6}" y="${mid}" text-anchor="end">${escapeXml(bar.label)}</text>`);
    if (bar.value === null || !Number.isFinite(bar.value)) {
      out.push(`<text x="${LABEL_WIDTH + 4}" y="${mid}" fill="#999">n/a</text>`);
      return;
    }
    const x0 = LABEL_WIDTH;
    const w = Math.max(1, axis.toX(bar.value) - x0);
    out.push(`<rect x="${x0}" y="${y}" width="${w.toFixed(1)}" height="${BAR_HEIGHT}" fill="${SERIES_COLORS[bar.series]}"/>`);
    out.push(`<text x="${(x0 + w + 4).toFixed(1)}" y="${mid}">${escapeXml(formatValue(bar.value))}</text>`);
  });
  if (chart.goal !== undefined) {
    const x = axis.toX(chart.goal).toFixed(1);
    out.push(`<line x1="${x}" y1="${TOP - 8}" x2="${x}" y2="${plotBottom}" stroke="#d03030" stroke-dasharray="4 3" stroke-width="1.5"/>`);
    out.push(`<text x="${x}" y="${TOP - 10}" text-anchor="middle" fill="#d03030">goal ${escapeXml(formatValue(chart.goal))}</text>`);
  }
  out.push('</svg>');
  return `${out.join('\n')}\n`;
}
