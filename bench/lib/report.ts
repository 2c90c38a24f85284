// Turns figure outputs into what people read: the one table the runner prints (plain text, aligned columns, goal
// and met/missed per row) and the markdown page bench/results/latest.md that embeds each figure's SVG chart.
import { meetsGoal, type Goal, type ReportRow } from './figure.ts';

/** Machine facts stored with every result. */
export interface MachineInfo {
  cpuModel: string;
  cores: number;
  nodeVersion: string;
  platform: string;
  totalMemoryMiB: number;
  /** 1-minute load average when the run started (noise from other processes). */
  loadAverage1m: number;
  /** /proc/loadavg as read when the run started and when it ended (the 1/5/15-minute averages where it is missing). */
  loadAtStart: string;
  loadAtEnd: string | null;
  /** What the load means for the figures (see describeLoad). */
  loadNote: string;
}

/** Busier than this many runnable tasks per core on average and wall-clock figures are not to be trusted. */
export const BUSY_LOAD_PER_CORE = 0.5;

/** A sentence on the machine's load over a run, from the 1-minute averages at its start and end. */
export function describeLoad(cores: number, startLoad1m: number, endLoad1m: number | null): string {
  const worst = Math.max(startLoad1m, endLoad1m ?? startLoad1m);
  const text = `1-minute load ${startLoad1m.toFixed(2)} at start${endLoad1m === null ? '' : `, ${endLoad1m.toFixed(2)} at end`} on ${cores} core${cores === 1 ? '' : 's'}`;
  if (worst > cores * BUSY_LOAD_PER_CORE) return `${text}: other work shared the machine, so wall-clock figures (tick times, clients and rooms per core) are noisy and understate what a quiet machine does; rerun at a quiet time before comparing.`;
  return `${text}: quiet.`;
}

/** How one figure's process went. */
export interface FigureStatus {
  status: 'ok' | 'failed' | 'skipped';
  seconds: number;
  error?: string;
}

/** A figure's section on the results page. */
export interface PageSection {
  title: string;
  /** SVG file names (relative to the page). */
  charts: string[];
  notes: string[];
  status: FigureStatus;
}

/** "≤ 1.10" for a goal. */
export function formatGoal(goal: Goal | undefined, digits: number): string {
  if (!goal) return '';
  return `${goal.op === '<=' ? '≤' : '≥'} ${goal.value.toFixed(digits)}`;
}

/** The value cell of a row. */
export function formatRowValue(row: ReportRow): string {
  if (row.value === null || !Number.isFinite(row.value)) return 'n/a';
  const text = row.value.toFixed(row.digits);
  return row.unit === '' || row.unit === '×' ? (row.unit === '×' ? `${text}×` : text) : `${text} ${row.unit}`;
}

function metCell(row: ReportRow): string {
  const met = meetsGoal(row.value, row.goal);
  if (met === null) return row.goal ? '?' : '';
  return met ? 'met' : 'MISSED';
}

function cells(row: ReportRow): string[] {
  return [row.figure, row.measure, formatRowValue(row), formatGoal(row.goal, row.digits), metCell(row)];
}

const HEADER = ['figure', 'measure', 'value', 'goal', ''];

/** The results as one aligned plain-text table. */
export function renderTable(rows: readonly ReportRow[]): string {
  const all = [HEADER, ...rows.map(cells)];
  const widths = HEADER.map((_, c) => Math.max(...all.map((r) => [...r[c]].length)));
  const line = (r: string[]): string => r.map((cell, c) => cell + ' '.repeat(widths[c] - [...cell].length)).join('  ').trimEnd();
  const rule = widths.map((w) => '-'.repeat(w)).join('  ');
  return [line(HEADER), rule, ...rows.map((r) => line(cells(r)))].join('\n') + '\n';
}

function mdEscape(text: string): string {
  return text.replace(/\|/g, '\\|');
}

/** The results as a markdown table. */
export function renderMarkdownTable(rows: readonly ReportRow[]): string {
  const head = '| figure | measure | value | goal | |\n|---|---|---|---|---|';
  const body = rows.map((r) => `| ${cells(r).map(mdEscape).join(' | ')} |`);
  return [head, ...body].join('\n') + '\n';
}

/** The whole results page. */
export function renderMarkdownPage(opts: { quick: boolean; startedAt: string; durationSeconds: number; machine: MachineInfo; rows: readonly ReportRow[]; sections: readonly PageSection[] }): string {
  const m = opts.machine;
  const parts: string[] = [];
  parts.push('# Benchmark results', '');
  parts.push(`${opts.quick ? 'Quick run (coarse: fewer samples, shorter scenes)' : 'Full run'} started ${opts.startedAt}, took ${opts.durationSeconds.toFixed(0)} s.`);
  parts.push(`Machine: ${m.cpuModel}, ${m.cores} cores, ${m.totalMemoryMiB} MiB, ${m.platform}, Node ${m.nodeVersion}.`);
  parts.push(`Load (/proc/loadavg): \`${m.loadAtStart}\` at start, \`${m.loadAtEnd ?? 'n/a'}\` at end. ${m.loadNote}`);
  parts.push('How each figure is measured: [bench/README.md](../README.md). Regenerate with `npm run bench`.', '');
  parts.push(renderMarkdownTable(opts.rows));
  for (const s of opts.sections) {
    parts.push(`## ${s.title}`, '');
    if (s.status.status !== 'ok') parts.push(`**${s.status.status}**${s.status.error ? `: ${s.status.error}` : ''}`, '');
    for (const c of s.charts) parts.push(`![${s.title}](${c})`, '');
    for (const n of s.notes) parts.push(`- ${n}`);
    if (s.notes.length > 0) parts.push('');
  }
  return `${parts.join('\n').trimEnd()}\n`;
}
