// The heads-up display: net mode, server tick, RTT, snapshot rate, kbps in, interpolation delay, predicted play's
// input delay, rollback depth, re-sim time, corrections and desyncs, bodies, FPS, the net graph, and the event feed.
// DOM text only (never HTML from the network); refreshed a few times a second, not every frame.
import type { PredictionStats } from '../../sdk/index.ts';
import { drawNetGraph } from './net-graph.ts';
import type { NetHistory } from './net-history.ts';

/** The numbers the HUD shows. */
export interface HudValues {
  serverTick: number;
  rttMs: number | null;
  inputLeadTicks: number | null;
  /** The room's ticks per second and whether it runs slowed (server's word, last pong). */
  roomPace: { ticksPerSecond: number; slow: boolean } | null;
  snapshotsPerSecond: number;
  kbpsIn: number;
  interpolationDelayMs: number;
  bufferDepth: number;
  bodies: number;
  fps: number;
  frameMs: number;
  playerId: number | null;
  room: string;
  /** How the room is played: 'snapshot', or the predicting client's mode ('starting', 'predict', 'resyncing', …). */
  netMode: string;
  /** Predicted play's numbers; null in snapshot rooms. */
  prediction: PredictionStats | null;
}

/** A HUD row; `when` limits it to predicted play or to snapshot play. */
type Row = [key: string, label: string, format: (v: HudValues) => string, when?: 'predict' | 'snapshot'];

/** The prediction numbers of a row shown only while predicting. */
const prediction = (v: HudValues): PredictionStats => v.prediction!;

const ROWS: readonly Row[] = [
  ['room', 'room', (v) => v.room],
  ['netMode', 'net mode', (v) => (v.prediction?.mode === 'snapshot' ? `snapshot (fell back: ${v.prediction.reason ?? 'budget'})` : v.netMode)],
  ['playerId', 'player', (v) => (v.playerId === null ? 'spectating' : `#${v.playerId}`)],
  ['serverTick', 'server tick', (v) => String(v.serverTick)],
  ['rttMs', 'RTT', (v) => (v.rttMs === null ? '…' : `${v.rttMs.toFixed(0)} ms`)],
  ['inputLeadTicks', 'input lead', (v) => (v.inputLeadTicks === null ? '…' : `${v.inputLeadTicks.toFixed(2)} ticks`)],
  ['roomPace', 'room rate', (v) => (v.roomPace === null ? '…' : `${v.roomPace.ticksPerSecond} ticks/s${v.roomPace.slow ? ' (slowed: the server cannot keep up)' : ''}`)],
  ['snapshotsPerSecond', 'snapshots', (v) => `${v.snapshotsPerSecond.toFixed(0)} /s`, 'snapshot'],
  ['kbpsIn', 'in', (v) => `${v.kbpsIn.toFixed(1)} kbps`],
  ['interpolationDelayMs', 'interp delay', (v) => `${v.interpolationDelayMs.toFixed(0)} ms (${v.bufferDepth} ahead)`, 'snapshot'],
  ['inputDelay', 'input delay', (v) => `${prediction(v).inputDelayTicks} ticks`, 'predict'],
  ['rollback', 'rollback', (v) => `${prediction(v).rollbackDepth} ticks (p99 ${prediction(v).rollbackDepthP99})`, 'predict'],
  ['resim', 're-sim', (v) => `${prediction(v).resimMs.toFixed(2)} ms (p99 ${prediction(v).resimMsP99.toFixed(2)})`, 'predict'],
  ['corrections', 'corrections', (v) => String(prediction(v).corrections), 'predict'],
  ['desyncs', 'desyncs', (v) => String(prediction(v).desyncs), 'predict'],
  ['bodies', 'bodies', (v) => String(v.bodies)],
  ['fps', 'FPS', (v) => `${v.fps.toFixed(0)} (${v.frameMs.toFixed(1)} ms)`],
];

const FEED_LINES = 6;

/** Owns the #hud, #netgraph and #feed elements' contents. */
export class Hud {
  private readonly root: HTMLElement;
  private readonly cells = new Map<string, HTMLElement>();
  private readonly rows = new Map<string, HTMLElement>();
  private readonly graph: HTMLCanvasElement;
  private readonly feed: HTMLElement;
  private readonly lines: string[] = [];
  private lastRefreshMs = -Infinity;

  constructor(root: HTMLElement, feed: HTMLElement) {
    this.root = root;
    this.feed = feed;
    root.replaceChildren();
    for (const [key, label] of ROWS) {
      const row = document.createElement('div');
      row.className = 'row';
      const name = document.createElement('span');
      name.textContent = label;
      const value = document.createElement('span');
      value.dataset.field = key;
      row.append(name, value);
      root.append(row);
      this.cells.set(key, value);
      this.rows.set(key, row);
    }
    this.graph = document.createElement('canvas');
    this.graph.id = 'netgraph';
    this.graph.title = 'snapshot arrival jitter (bars) and interpolation buffer depth (line), last 5 s';
    root.append(this.graph);
  }

  /** Shows or hides the HUD and feed. */
  set visible(on: boolean) {
    this.root.hidden = !on;
    this.feed.hidden = !on;
  }

  /** Updates the numbers and the graph, at most every `intervalMs`. */
  refresh(nowMs: number, values: HudValues, history: NetHistory, intervalMs = 250): void {
    if (nowMs - this.lastRefreshMs < intervalMs) return;
    this.lastRefreshMs = nowMs;
    const predicting = values.prediction !== null && values.prediction.mode !== 'snapshot';
    for (const [key, , format, when] of ROWS) {
      const cell = this.cells.get(key);
      const shown = when === undefined || (when === 'predict') === predicting;
      this.rows.get(key)!.hidden = !shown;
      if (cell && shown) cell.textContent = format(values);
    }
    drawNetGraph(this.graph, history, nowMs);
  }

  /** Adds a line to the event feed (newest last). */
  log(line: string): void {
    this.lines.push(line);
    if (this.lines.length > FEED_LINES) this.lines.splice(0, this.lines.length - FEED_LINES);
    this.feed.replaceChildren(
      ...this.lines.map((l) => {
        const div = document.createElement('div');
        div.textContent = l;
        return div;
      }),
    );
  }

  /** The feed's current lines. */
  feedLines(): string[] {
    return [...this.lines];
  }
}
