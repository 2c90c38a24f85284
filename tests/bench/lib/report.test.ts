// Tests for the bench's printed table and results page: aligned columns, goals with met/MISSED, missing values,
// markdown escaping, and each figure's charts, notes and failures on the page.
import { describe, expect, it } from 'vitest';
import type { ReportRow } from '../../../bench/lib/figure.ts';
import { describeLoad, formatGoal, formatRowValue, renderMarkdownPage, renderMarkdownTable, renderTable } from '../../../bench/lib/report.ts';

const rows: ReportRow[] = [
  { figure: 'tick overhead', measure: 'median ratio, 16 clients', value: 1.234, unit: '×', digits: 2, goal: { op: '<=', value: 1.1 } },
  { figure: 'bandwidth', measure: 'ours, 60 Hz', value: 73.66, unit: 'kbps', digits: 1, goal: { op: '<=', value: 128 } },
  { figure: 'clients per core', measure: 'largest passing', value: null, unit: '', digits: 0, goal: { op: '>=', value: 256 } },
  { figure: 'determinism cost', measure: 'hash | per tick', value: 0.5, unit: 'ms', digits: 3 },
];

const machine = { cpuModel: 'Test CPU', cores: 2, nodeVersion: 'v24.0.0', platform: 'linux', totalMemoryMiB: 1024, loadAverage1m: 0.5, loadAtStart: '0.50 0.40 0.30 1/90 123', loadAtEnd: '3.10 1.20 0.60 2/95 456', loadNote: 'busy' };

describe('report', () => {
  it('marks each goal met or MISSED, and unknown when there is no value', () => {
    const text = renderTable(rows);
    const lines = text.trimEnd().split('\n');
    expect(lines[2]).toMatch(/tick overhead .* 1\.23× +≤ 1\.10 +MISSED$/);
    expect(lines[3]).toMatch(/bandwidth .* 73\.7 kbps +≤ 128\.0 +met$/);
    expect(lines[4]).toMatch(/clients per core .* n\/a +≥ 256 +\?$/);
    expect(lines[5]).toMatch(/determinism cost .* 0\.500 ms$/);
  });

  it('aligns every column under its header', () => {
    const lines = renderTable(rows).trimEnd().split('\n');
    const valueColumn = lines[0].indexOf('value');
    for (const line of lines.slice(2)) expect([...line].slice(valueColumn - 2, valueColumn).join('')).toBe('  ');
    expect(lines[1]).toMatch(/^-+ {2}-+/);
  });

  it('formats goals and values with the row’s decimals and unit', () => {
    expect(formatGoal({ op: '>=', value: 256 }, 0)).toBe('≥ 256');
    expect(formatGoal(undefined, 2)).toBe('');
    expect(formatRowValue(rows[0])).toBe('1.23×');
    expect(formatRowValue(rows[1])).toBe('73.7 kbps');
    expect(formatRowValue({ ...rows[2], value: 300 })).toBe('300');
    expect(formatRowValue({ ...rows[1], value: Number.NaN })).toBe('n/a');
  });

  it('escapes pipes in markdown cells', () => {
    const md = renderMarkdownTable(rows);
    expect(md).toContain('hash \\| per tick');
    expect(md.split('\n')[1]).toBe('|---|---|---|---|---|');
  });

  it('puts machine, table, charts, notes and failures on the page', () => {
    const page = renderMarkdownPage({
      quick: true,
      startedAt: '2026-01-01T00:00:00.000Z',
      durationSeconds: 61.4,
      machine,
      rows,
      sections: [
        { title: 'bandwidth', charts: ['bandwidth.svg'], notes: ['acks after 100 ms'], status: { status: 'ok', seconds: 12 } },
        { title: 'replay', charts: [], notes: [], status: { status: 'failed', seconds: 3, error: 'ran past its limit' } },
      ],
    });
    expect(page).toMatch(/^# Benchmark results/);
    expect(page).toContain('Quick run');
    expect(page).toContain('took 61 s');
    expect(page).toContain('Test CPU, 2 cores');
    expect(page).toContain('`0.50 0.40 0.30 1/90 123` at start, `3.10 1.20 0.60 2/95 456` at end. busy');
    expect(page).toContain('![bandwidth](bandwidth.svg)');
    expect(page).toContain('- acks after 100 ms');
    expect(page).toContain('**failed**: ran past its limit');
    expect(page.endsWith('\n')).toBe(true);
  });

  it('calls a run quiet only while the load stays under half a task per core at start and end', () => {
    expect(describeLoad(2, 0.4, 0.9)).toBe('1-minute load 0.40 at start, 0.90 at end on 2 cores: quiet.');
    expect(describeLoad(2, 0.4, 2.5)).toMatch(/^1-minute load 0\.40 at start, 2\.50 at end on 2 cores: other work shared the machine/);
    expect(describeLoad(1, 0.7, null)).toMatch(/^1-minute load 0\.70 at start on 1 core: other work/);
  });
});
