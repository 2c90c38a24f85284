// The contract between the bench runner and each figure: what a figure is (name, title, time limit, run) and what
// it hands back (headline keys for latest.json, its detail, table rows, a chart, notes). Plain data only.

/** A goal a measured value is held to. */
export interface Goal {
  op: '<=' | '>=';
  value: number;
}

/** One line of the printed table. */
export interface ReportRow {
  /** Figure title, e.g. "tick overhead". */
  figure: string;
  /** What was measured, e.g. "median ratio, shape-rain 1000, 16 clients". */
  measure: string;
  /** The value, or null when it could not be measured (see the figure's notes). */
  value: number | null;
  unit: string;
  /** Decimals to print. */
  digits: number;
  goal?: Goal;
}

/** One bar of a chart. */
export interface ChartBar {
  label: string;
  value: number | null;
  /** Colour class: our system, a baseline/peer, or the raw engine floor. */
  series: 'ours' | 'baseline' | 'raw' | 'other';
}

/** A small horizontal bar chart (rendered by svg.ts). */
export interface Chart {
  title: string;
  unit: string;
  bars: ChartBar[];
  /** Draw a dashed goal line at this value. */
  goal?: number;
  /** Log axis (for values spanning orders of magnitude). */
  log?: boolean;
}

/** What a figure returns. */
export interface FigureOutput {
  /** Top-level keys of latest.json this figure owns (e.g. tickOverheadRatio16); null when not measured. */
  headline: Record<string, number | null>;
  /** The figure's detail, stored under its own key in latest.json. */
  detail: Record<string, unknown>;
  rows: ReportRow[];
  charts: Chart[];
  /** Anything the reader must know (a quick run's shortcuts, what could not be measured and why). */
  notes: string[];
}

/** Options every figure gets. */
export interface FigureOptions {
  /** The coarse, about-a-minute run. */
  quick: boolean;
  /** Progress lines (stderr). */
  log(message: string): void;
}

/** One benchmark figure. */
export interface FigureSpec {
  /** Kebab-case id used by --only. */
  name: string;
  /** Human title used in the table. */
  title: string;
  /** Key of the figure's detail object in latest.json. */
  detailKey: string;
  /** Headline keys the figure fills (listed so a failed figure still writes them as null). */
  headlineKeys: readonly string[];
  /** Runs only with --peers. */
  peersOnly?: boolean;
  /** Wall-clock limit of the figure's process (ms). */
  timeLimitMs(quick: boolean): number;
  /** Module path (relative to bench/) exporting `figure: FigureImpl`. */
  module: string;
}

/** The code of a figure (loaded in the figure's own process). */
export interface FigureImpl {
  run(opts: FigureOptions): Promise<FigureOutput>;
}

/** Whether `value` meets `goal` (null when there is no value or no goal). */
export function meetsGoal(value: number | null, goal: Goal | undefined): boolean | null {
  if (goal === undefined || value === null || !Number.isFinite(value)) return null;
  return goal.op === '<=' ? value <= goal.value : value >= goal.value;
}
