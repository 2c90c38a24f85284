// The HUD's net graph: snapshot arrival jitter (bars, ms) and interpolation buffer depth (line, snapshots) over the
// last seconds, drawn with a 2-D canvas: a legend row above the plot, each axis labelled in its own margin (left: ms,
// right: snapshots), a dashed line at one tick, so no label ever sits on the data. Reads a NetHistory; owns only its
// canvas drawing.
import type { NetHistory, SeriesPoint } from './net-history.ts';

const JITTER_SCALE_MS = 50;
const DEPTH_SCALE = 8;
/** Layout in CSS pixels (scaled by the device pixel ratio). */
const LEGEND_PX = 16;
const LEFT_AXIS_PX = 30;
const RIGHT_AXIS_PX = 16;
const BOTTOM_PX = 3;
const GOOD = '#5fd47a';
const FAIR = '#f0c04a';
const BAD = '#ff6b5e';
const DEPTH = '#7fb6ff';
const TEXT = 'rgba(232, 237, 242, 0.85)';

/** Draws `history` into `canvas` (sized by CSS; the backing store follows it). */
export function drawNetGraph(canvas: HTMLCanvasElement, history: NetHistory, nowMs: number): void {
  const ctx = canvas.getContext('2d');
  if (!ctx) return;
  const dpr = Math.min(globalThis.devicePixelRatio || 1, 2);
  const w = Math.max(1, Math.round(canvas.clientWidth * dpr));
  const h = Math.max(1, Math.round(canvas.clientHeight * dpr));
  if (canvas.width !== w) canvas.width = w;
  if (canvas.height !== h) canvas.height = h;
  ctx.clearRect(0, 0, w, h);
  const plot = { left: LEFT_AXIS_PX * dpr, top: LEGEND_PX * dpr, right: w - RIGHT_AXIS_PX * dpr, bottom: h - BOTTOM_PX * dpr };
  const plotW = Math.max(1, plot.right - plot.left);
  const plotH = Math.max(1, plot.bottom - plot.top);
  ctx.fillStyle = 'rgba(0, 0, 0, 0.35)';
  ctx.fillRect(plot.left, plot.top, plotW, plotH);
  const x = (t: number): number => plot.right - ((nowMs - t) / history.windowMs) * plotW;
  const yMs = (ms: number): number => plot.bottom - (Math.min(ms, JITTER_SCALE_MS) / JITTER_SCALE_MS) * plotH;
  const { jitter, depth } = history.series();

  // One tick: below it the arrival was on time.
  ctx.strokeStyle = 'rgba(232, 237, 242, 0.35)';
  ctx.lineWidth = dpr;
  ctx.setLineDash([3 * dpr, 3 * dpr]);
  ctx.beginPath();
  ctx.moveTo(plot.left, yMs(history.tickMs));
  ctx.lineTo(plot.right, yMs(history.tickMs));
  ctx.stroke();
  ctx.setLineDash([]);

  // Jitter bars: green under a tick, amber under 3 ticks, red beyond.
  const barW = Math.max(2 * dpr, plotW / 150);
  ctx.save();
  ctx.beginPath();
  ctx.rect(plot.left, plot.top, plotW, plotH);
  ctx.clip();
  for (const p of jitter) {
    ctx.fillStyle = p.value < history.tickMs ? GOOD : p.value < 3 * history.tickMs ? FAIR : BAD;
    const top = yMs(p.value);
    ctx.fillRect(x(p.timeMs) - barW / 2, top, barW, plot.bottom - top);
  }
  drawLine(ctx, depth, x, (v) => plot.bottom - (Math.min(v, DEPTH_SCALE) / DEPTH_SCALE) * plotH, DEPTH, dpr);
  ctx.restore();

  // Axes, in their own margins.
  ctx.font = `${10 * dpr}px ui-monospace, monospace`;
  ctx.textBaseline = 'middle';
  ctx.fillStyle = TEXT;
  ctx.textAlign = 'right';
  ctx.fillText(`${JITTER_SCALE_MS}ms`, plot.left - 3 * dpr, plot.top + 5 * dpr);
  ctx.fillText('0', plot.left - 3 * dpr, plot.bottom - 5 * dpr);
  ctx.fillStyle = DEPTH;
  ctx.textAlign = 'left';
  ctx.fillText(String(DEPTH_SCALE), plot.right + 3 * dpr, plot.top + 5 * dpr);
  ctx.fillText('0', plot.right + 3 * dpr, plot.bottom - 5 * dpr);

  // Legend row above the plot.
  let lx = plot.left;
  const ly = (LEGEND_PX / 2) * dpr;
  const item = (color: string, label: string, line = false): void => {
    ctx.fillStyle = color;
    if (line) ctx.fillRect(lx, ly - dpr, 9 * dpr, 2 * dpr);
    else ctx.fillRect(lx, ly - 4 * dpr, 8 * dpr, 8 * dpr);
    ctx.fillStyle = TEXT;
    ctx.textAlign = 'left';
    ctx.fillText(label, lx + 11 * dpr, ly);
    lx += 11 * dpr + ctx.measureText(label).width + 8 * dpr;
  };
  item(GOOD, 'jitter <1 tick');
  item(FAIR, '<3');
  item(BAD, '≥3');
  item(DEPTH, 'buffer', true);
}

function drawLine(ctx: CanvasRenderingContext2D, pts: readonly SeriesPoint[], x: (t: number) => number, y: (v: number) => number, color: string, dpr: number): void {
  if (pts.length === 0) return;
  ctx.strokeStyle = color;
  ctx.lineWidth = 2 * dpr;
  ctx.beginPath();
  pts.forEach((p, i) => {
    if (i === 0) ctx.moveTo(x(p.timeMs), y(p.value));
    else ctx.lineTo(x(p.timeMs), y(p.value));
  });
  ctx.stroke();
}
