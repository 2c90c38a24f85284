// Assembles latest.json from the figures' outputs: one top-level key per headline figure in the issue's order
// (null when a figure failed or did not run), then machine and quick, then each figure's detail under its own key.
import type { FigureOutput, FigureSpec, ReportRow } from './figure.ts';
import type { FigureStatus, MachineInfo } from './report.ts';

/** One figure's run: its spec, how it went and (when it succeeded) its output. */
export interface FigureRun {
  spec: FigureSpec;
  status: FigureStatus;
  output: FigureOutput | null;
}

/** The object written to latest.json and printed by --json. */
export type BenchResults = Record<string, unknown> & {
  machine: MachineInfo;
  quick: boolean;
};

/** Builds the results object. Headline keys come first (in `headlineKeys` order), every one present. */
export function assembleResults(opts: { headlineKeys: readonly string[]; runs: readonly FigureRun[]; machine: MachineInfo; quick: boolean; startedAt: string; durationSeconds: number }): BenchResults {
  const headline: Record<string, number | null> = {};
  for (const key of opts.headlineKeys) headline[key] = null;
  for (const run of opts.runs) {
    if (!run.output) continue;
    for (const [key, value] of Object.entries(run.output.headline)) {
      if (!(key in headline)) throw new Error(`figure ${run.spec.name} reports headline key "${key}" that latest.json does not list`);
      headline[key] = value === null || Number.isFinite(value) ? value : null;
    }
  }
  const results: BenchResults = {
    ...headline,
    machine: opts.machine,
    quick: opts.quick,
    startedAt: opts.startedAt,
    durationSeconds: Math.round(opts.durationSeconds),
    figures: Object.fromEntries(opts.runs.map((r) => [r.spec.name, r.status])),
    rows: allRows(opts.runs),
  };
  for (const run of opts.runs) {
    if (run.output) results[run.spec.detailKey] = { ...run.output.detail, notes: run.output.notes };
  }
  return results;
}

/** Every figure's table rows in run order; a figure that failed gets one row per headline key with no value. */
export function allRows(runs: readonly FigureRun[]): ReportRow[] {
  const rows: ReportRow[] = [];
  for (const run of runs) {
    if (run.output) rows.push(...run.output.rows);
    else if (run.status.status === 'failed') {
      const keys = run.spec.headlineKeys.length > 0 ? run.spec.headlineKeys : [run.spec.name];
      for (const key of keys) rows.push({ figure: run.spec.title, measure: `${key} (figure failed)`, value: null, unit: '', digits: 0 });
    }
  }
  return rows;
}
