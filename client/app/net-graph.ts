// The HUD's net graph: snapshot arrival jitter (bars, ms) and interpolation buffer depth (line, snapshots) over the
// last seconds, drawn with a 2-D canvas. Reads a NetHistory; owns only its canvas drawing.
import type { NetHistory, SeriesPoint } from './net-history.ts';

const JITTER_SCALE_MS = 50;
const DEPTH_SCALE = 8;

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
  ctx.fillStyle = 'rgba(0, 0, 0, 0.35)';
  ctx.fillRect(0, 0, w, h);
  const x = (t: number): number => w - ((nowMs - t) / history.windowMs) * w;
  const { jitter, depth } = history.series();

  // Jitter bars: green under a tick, amber under 3 ticks, red beyond.
  const barW = Math.max(1, dpr);
  for (const p of jitter) {
    const v = Math.min(p.value, JITTER_SCALE_MS);
    ctx.fillStyle = p.value < history.tickMs ? '#5fd47a' : p.value < 3 * history.tickMs ? '#f0c04a' : '#ff6b5e';
    const bh = (v / JITTER_SCALE_MS) * (h - 2);
    ctx.fillRect(x(p.timeMs) - barW / 2, h - bh, barW, bh);
  }
  drawLine(ctx, depth, x, (v) => h - 1 - (Math.min(v, DEPTH_SCALE) / DEPTH_SCALE) * (h - 2), '#7fb6ff', dpr);

  ctx.fillStyle = 'rgba(232, 237, 242, 0.8)';
  ctx.font = `${10 * dpr}px ui-monospace, monospace`;
  ctx.fillText(`jitter 0–${JITTER_SCALE_MS} ms`, 4 * dpr, 11 * dpr);
  ctx.fillStyle = '#7fb6ff';
  ctx.fillText(`buffer 0–${DEPTH_SCALE}`, w - 62 * dpr, 11 * dpr);
}

function drawLine(ctx: CanvasRenderingContext2D, pts: readonly SeriesPoint[], x: (t: number) => number, y: (v: number) => number, color: string, dpr: number): void {
  if (pts.length === 0) return;
  ctx.strokeStyle = color;
  ctx.lineWidth = 1.5 * dpr;
  ctx.beginPath();
  pts.forEach((p, i) => {
    if (i === 0) ctx.moveTo(x(p.timeMs), y(p.value));
    else ctx.lineTo(x(p.timeMs), y(p.value));
  });
  ctx.stroke();
}
