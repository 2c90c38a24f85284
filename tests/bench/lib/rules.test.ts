// Tests for the bench's pass rules and derived figures: client and room windows, GC pause per tick, the per-client
// cost line, and the input-latency distribution that keeps unapplied (late) inputs in.
import { describe, expect, it } from 'vitest';
import { clientCost, gcPauseInSpans, gcPausePerTick, judgeClientWindow, judgeRoomsWindow, judgeSwarmProof, ladderResult, latencyDistribution, maxClientGapMs, maxGap, nextLadderCount, TICK_BUDGET_MS } from '../../../bench/lib/rules.ts';

const goodWindow = { seconds: 8, ticks: 480, tickP99Ms: 12, snapshotsSent: 30 * 8 * 100, snapshotsSkipped: 0, droppedClients: 0 };

describe('rules', () => {
  it('passes a client window that ran 60 ticks/s with tick p99 under 16.7 ms', () => {
    expect(judgeClientWindow(goodWindow)).toEqual({ pass: true, reasons: [] });
  });

  it('fails a client window whose ticks per second fell below 60 even when every tick was fast', () => {
    const v = judgeClientWindow({ ...goodWindow, ticks: 440, tickP99Ms: 3 });
    expect(v.pass).toBe(false);
    expect(v.reasons).toEqual(['55.0 ticks/s < 60']);
  });

  it('fails a client window at a tick p99 of exactly one tick budget', () => {
    const v = judgeClientWindow({ ...goodWindow, tickP99Ms: TICK_BUDGET_MS });
    expect(v.pass).toBe(false);
    expect(v.reasons[0]).toMatch(/^tick p99 16\.7 ms/);
  });

  it('fails a client window with skipped snapshots over 1%, dropped clients, or no ticks at all', () => {
    expect(judgeClientWindow({ ...goodWindow, snapshotsSkipped: 300 }).reasons).toEqual(['1.2% of snapshots skipped']);
    expect(judgeClientWindow({ ...goodWindow, droppedClients: 2 }).reasons).toEqual(['2 clients dropped']);
    const none = judgeClientWindow({ ...goodWindow, ticks: 0, tickP99Ms: null, snapshotsSent: 0 });
    expect(none.pass).toBe(false);
    expect(none.reasons).toHaveLength(3);
  });

  const rule = { botsPerRoom: 4, snapshotIntervalTicks: 2 };
  const room = { id: 'a', ticks: 300, maxGapMs: 2 * TICK_BUDGET_MS, tickP99Ms: 3, clients: 4, snapshots: 600, clientGapMs: 60, clientTickStep: 2 };

  it('passes a room count only when every room keeps its tick starts at most two ticks apart', () => {
    expect(judgeRoomsWindow(5, [room, { ...room, id: 'b' }], rule)).toEqual({ pass: true, reasons: [] });
    const v = judgeRoomsWindow(5, [room, { ...room, id: 'b', maxGapMs: 40 }], rule);
    expect(v.pass).toBe(false);
    expect(v.reasons).toEqual(['1 room(s) with a tick gap > 2 ticks (worst 40.0 ms)']);
  });

  it('fails a room count where a room fell below 60 ticks/s or ran fewer than two ticks', () => {
    expect(judgeRoomsWindow(5, [{ ...room, ticks: 250, maxGapMs: 20 }], rule).reasons).toEqual(['1 room(s) below 60 ticks/s']);
    expect(judgeRoomsWindow(5, [{ ...room, ticks: 1, maxGapMs: null }], rule).pass).toBe(false);
    expect(judgeRoomsWindow(5, [], rule).pass).toBe(false);
  });

  it('fails a room whose tick p99 reaches one tick budget although its ticks kept their spacing', () => {
    expect(judgeRoomsWindow(5, [{ ...room, tickP99Ms: TICK_BUDGET_MS }], rule).reasons).toEqual(['1 room(s) with tick p99 ≥ 16.7 ms (worst 16.7 ms)']);
  });

  it('fails a room whose clients waited more than the snapshot spacing plus two ticks, or missed a snapshot', () => {
    expect(maxClientGapMs(2)).toBeCloseTo(66.67, 2);
    expect(judgeRoomsWindow(5, [{ ...room, clientGapMs: 70 }], rule).reasons).toEqual(['1 room(s) whose clients waited > 66.7 ms for a snapshot (worst 70.0 ms)']);
    expect(judgeRoomsWindow(5, [{ ...room, clientTickStep: 4 }], rule).reasons).toEqual(['1 room(s) whose clients missed a snapshot']);
    expect(judgeRoomsWindow(5, [{ ...room, clientGapMs: null, clientTickStep: null }], rule).pass).toBe(false);
  });

  it('fails a room holding players left over from an earlier step', () => {
    expect(judgeRoomsWindow(5, [{ ...room, clients: 8 }], rule).reasons).toEqual(['1 room(s) without exactly 4 players']);
  });

  it('finds the longest gap between ascending times', () => {
    expect(maxGap([0, 16, 50, 60])).toBe(34);
    expect(maxGap([5])).toBeNull();
  });

  it('adds each GC pause to the tick interval it started in and ignores pauses outside the window', () => {
    const perTick = gcPausePerTick(
      1000,
      1100,
      [
        { startTime: 999, duration: 5 },
        { startTime: 1001, duration: 1 },
        { startTime: 1010, duration: 2 },
        { startTime: 1020, duration: 30 },
        { startTime: 1100, duration: 9 },
      ],
      10,
    );
    expect(perTick).toEqual([1, 2, 30, 0, 0, 0, 0, 0, 0, 0]);
  });

  it('fits server CPU per tick against clients as a fixed part plus a cost per client', () => {
    const cost = clientCost([
      { clients: 16, cpuMsPerTick: 1 + 16 * 0.025 },
      { clients: 64, cpuMsPerTick: 1 + 64 * 0.025 },
      { clients: 128, cpuMsPerTick: 1 + 128 * 0.025 },
    ]);
    expect(cost!.usPerClientTick).toBeCloseTo(25, 9);
    expect(cost!.fixedMsPerTick).toBeCloseTo(1, 9);
    expect(cost!.r2).toBeCloseTo(1, 9);
    expect(clientCost([{ clients: 16, cpuMsPerTick: 2 }, { clients: 16, cpuMsPerTick: 3 }])).toBeNull();
  });

  it('ranks inputs that were never applied after every applied one in the latency distribution', () => {
    const d = latencyDistribution([1, 1, 2, 1], 1);
    expect(d).toMatchObject({ inputs: 5, applied: 4, notApplied: 1, notAppliedShare: 0.2, median: 1, max: null });
    expect(d.p99).toBeNull();
    expect(d.histogram).toEqual({ '1': 3, '2': 1, late: 1 });
  });

  it('gives the plain quantiles when every input was applied', () => {
    const d = latencyDistribution([2, 1, 1, 3], 0);
    expect(d.median).toBe(1.5);
    expect(d.max).toBe(3);
    expect(d.histogram).toEqual({ '1': 2, '2': 1, '3': 1 });
  });

  it('moves the median onto the late inputs once they are half or more of the inputs', () => {
    expect(latencyDistribution([1, 1], 3).median).toBeNull();
    expect(latencyDistribution([], 0).median).toBeNull();
  });
});

describe('rules: swarm proof and ladder search', () => {
  const real = { cpuMsPerTick: 2, messagesPerClientPerSecond: 91, bytesPerClientPerSecond: 4000 };

  it('accepts a light swarm whose load on the server is within 10% of real clients on every measure', () => {
    const v = judgeSwarmProof(real, { cpuMsPerTick: 2.1, messagesPerClientPerSecond: 91, bytesPerClientPerSecond: 3900 });
    expect(v.pass).toBe(true);
    expect(v.ratios.cpuMsPerTick).toBeCloseTo(1.05, 12);
  });

  it('rejects a light swarm that costs the server noticeably less than real clients', () => {
    const v = judgeSwarmProof(real, { cpuMsPerTick: 1.5, messagesPerClientPerSecond: 61, bytesPerClientPerSecond: 4000 });
    expect(v.pass).toBe(false);
    expect(v.reasons).toEqual(['cpuMsPerTick: light/real 0.750 outside 1 ± 0.1', 'messagesPerClientPerSecond: light/real 0.670 outside 1 ± 0.1']);
  });

  it('climbs the ladder in order while every rung passes', () => {
    expect(nextLadderCount([16, 32, 64], new Map(), 16)).toBe(16);
    expect(nextLadderCount([16, 32, 64], new Map([[16, true], [32, true]]), 16)).toBe(64);
    expect(nextLadderCount([16, 32, 64], new Map([[16, true], [32, true], [64, true]]), 16)).toBeNull();
  });

  it('halves the gap between the last pass and the first miss down to the resolution', () => {
    const results = new Map([[64, true], [128, true], [192, false]]);
    expect(nextLadderCount([64, 128, 192, 256], results, 16)).toBe(160);
    results.set(160, true);
    expect(nextLadderCount([64, 128, 192, 256], results, 16)).toBe(176);
    results.set(176, false);
    expect(nextLadderCount([64, 128, 192, 256], results, 16)).toBeNull();
    expect(ladderResult(results)).toBe(160);
  });

  it('reports 0 when the first rung misses and ignores passes above the first miss', () => {
    expect(ladderResult(new Map([[16, false]]))).toBe(0);
    expect(nextLadderCount([16, 32], new Map([[16, false]]), 16)).toBeNull();
    expect(ladderResult(new Map([[16, true], [32, false], [48, true]]))).toBe(16);
  });

  it('adds each GC pause to the span it started in and leaves out pauses between spans', () => {
    const spans = [
      { startMs: 10, endMs: 12 },
      { startMs: 20, endMs: 21 },
      { startMs: 30, endMs: 35 },
    ];
    const pauses = [
      { startTime: 33, duration: 4 },
      { startTime: 9, duration: 7 },
      { startTime: 10, duration: 0.5 },
      { startTime: 11.9, duration: 3 },
      { startTime: 12, duration: 8 },
      { startTime: 30, duration: 1 },
    ];
    expect(gcPauseInSpans(spans, pauses)).toEqual([3.5, 0, 5]);
  });

  it('refuses overlapping spans', () => {
    expect(() => gcPauseInSpans([{ startMs: 0, endMs: 5 }, { startMs: 4, endMs: 6 }], [])).toThrow(/span 1 starts before span 0 ends/);
  });
});
