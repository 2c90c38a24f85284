// Tests of the connection statistics behind the HUD and net graph: rates, bytes, jitter and buffer depth.
import { describe, expect, it } from 'vitest';
import { NetHistory } from '../../../client/app/net-history.ts';

describe('NetHistory', () => {
  it('counts snapshots and kilobits received in the last second', () => {
    const h = new NetHistory(60);
    for (let i = 0; i < 40; i++) {
      h.recordSnapshot(i * 50, i * 3);
      h.recordBytes(i * 50, 500);
    }
    // At t = 1950 ms the last second holds the arrivals 950 < t <= 1950: 1000, 1050, …, 1950 (20 of them).
    expect(h.snapshotsPerSecond(1950)).toBe(20);
    expect(h.kbpsIn(1950)).toBeCloseTo((20 * 500 * 8) / 1000, 6);
  });

  it('measures jitter against the interval the ticks imply, not against the previous arrival alone', () => {
    const h = new NetHistory(60);
    h.recordSnapshot(1000, 60);
    h.recordSnapshot(1050, 63); // 3 ticks = 50 ms: on time
    h.recordSnapshot(1130, 66); // 80 ms for 50 ms of ticks: 30 ms late
    h.recordSnapshot(1140, 69); // 10 ms for 50 ms: 40 ms early (a burst after the late one)
    const values = h.series().jitter.map((p) => Math.round(p.value));
    expect(values).toEqual([0, 30, 40]);
    expect(h.meanJitterMs()).toBeCloseTo(70 / 3, 0);
  });

  it('adds no jitter for duplicated or reordered snapshots', () => {
    const h = new NetHistory(60);
    h.recordSnapshot(0, 3);
    h.recordSnapshot(50, 6);
    h.recordSnapshot(55, 6); // duplicate
    h.recordSnapshot(60, 4); // older, reordered
    h.recordSnapshot(100, 9);
    expect(h.series().jitter.map((p) => Math.round(p.value))).toEqual([0, 0]);
  });

  it('forgets samples older than its window', () => {
    const h = new NetHistory(60, 2000);
    h.recordBufferDepth(0, 3);
    h.recordBufferDepth(1500, 2);
    h.recordBufferDepth(3000, 1);
    expect(h.series().depth.map((p) => p.value)).toEqual([2, 1]);
  });

  it('rejects a non-positive tick rate or window', () => {
    expect(() => new NetHistory(0)).toThrow(/must be > 0/);
    expect(() => new NetHistory(60, -1)).toThrow(/must be > 0/);
  });
});
