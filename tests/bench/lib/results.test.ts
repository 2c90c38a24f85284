// Tests for assembling latest.json: every headline key present and first in the order, null for figures
// that failed, details under each figure's key, and a refusal of undeclared headline keys.
import { describe, expect, it } from 'vitest';
import type { FigureOutput, FigureSpec } from '../../../bench/lib/figure.ts';
import { allRows, assembleResults, type FigureRun } from '../../../bench/lib/results.ts';

const spec = (name: string, headlineKeys: string[]): FigureSpec => ({ name, title: name.replace('-', ' '), detailKey: `${name}Detail`, headlineKeys, timeLimitMs: () => 1000, module: `figures/${name}.ts` });
const output = (headline: Record<string, number | null>): FigureOutput => ({
  headline,
  detail: { samples: 3 },
  rows: [{ figure: 'x', measure: 'm', value: 1, unit: '', digits: 0 }],
  charts: [],
  notes: ['a note'],
});
const machine = { cpuModel: 'cpu', cores: 2, nodeVersion: 'v24', platform: 'linux', totalMemoryMiB: 1, loadAverage1m: 0, loadAtStart: '0 0 0 1/1 1', loadAtEnd: null, loadNote: 'quiet' };

describe('results', () => {
  const runs: FigureRun[] = [
    { spec: spec('bandwidth', ['kbpsB', 'kbpsA']), status: { status: 'ok', seconds: 1 }, output: output({ kbpsA: 70.5, kbpsB: 20 }) },
    { spec: spec('replay', ['replayRatio']), status: { status: 'failed', seconds: 2, error: 'boom' }, output: null },
  ];

  it('writes every headline key first, in the given order, with null for what did not run', () => {
    const r = assembleResults({ headlineKeys: ['kbpsA', 'kbpsB', 'replayRatio', 'startupMs'], runs, machine, quick: true, startedAt: 't', durationSeconds: 10.4 });
    expect(Object.keys(r).slice(0, 6)).toEqual(['kbpsA', 'kbpsB', 'replayRatio', 'startupMs', 'machine', 'quick']);
    expect(r).toMatchObject({ kbpsA: 70.5, kbpsB: 20, replayRatio: null, startupMs: null, quick: true, durationSeconds: 10 });
  });

  it('keeps each figure’s detail and notes under its own key and records how each figure went', () => {
    const r = assembleResults({ headlineKeys: ['kbpsA', 'kbpsB', 'replayRatio'], runs, machine, quick: false, startedAt: 't', durationSeconds: 1 });
    expect(r.bandwidthDetail).toEqual({ samples: 3, notes: ['a note'] });
    expect(r.replayDetail).toBeUndefined();
    expect(r.figures).toEqual({ bandwidth: { status: 'ok', seconds: 1 }, replay: { status: 'failed', seconds: 2, error: 'boom' } });
  });

  it('turns non-finite headline values into null', () => {
    const bad: FigureRun[] = [{ spec: spec('bandwidth', ['kbpsA']), status: { status: 'ok', seconds: 1 }, output: output({ kbpsA: Number.NaN }) }];
    expect(assembleResults({ headlineKeys: ['kbpsA'], runs: bad, machine, quick: false, startedAt: 't', durationSeconds: 1 }).kbpsA).toBeNull();
  });

  it('refuses a headline key latest.json does not list', () => {
    expect(() => assembleResults({ headlineKeys: ['kbpsA'], runs, machine, quick: false, startedAt: 't', durationSeconds: 1 })).toThrow(/headline key "kbpsB"/);
  });

  it('gives a failed figure one empty row per headline key in the table', () => {
    const rows = allRows(runs);
    expect(rows).toHaveLength(2);
    expect(rows[1]).toMatchObject({ figure: 'replay', measure: 'replayRatio (figure failed)', value: null });
  });
});
