// Tests of the frame timer behind the HUD's FPS and the reported frame times.
import { describe, expect, it } from 'vitest';
import { FrameTimer } from '../../../client/app/frame-timer.ts';

describe('FrameTimer', () => {
  it('derives FPS and interval percentiles from frame start times', () => {
    const t = new FrameTimer(100);
    for (let i = 0; i <= 60; i++) t.record(i * 20, 2);
    const s = t.summary();
    expect(s.frames).toBe(61);
    expect(s.fps).toBeCloseTo(50, 6);
    expect(s.p50IntervalMs).toBe(20);
    expect(s.meanCpuMs).toBe(2);
  });

  it('keeps only the most recent window and reports slow frames in p95', () => {
    const t = new FrameTimer(10);
    let now = 0;
    for (let i = 0; i < 50; i++) t.record((now += 100), 1); // old, slow frames fall out of the window
    for (let i = 0; i < 9; i++) t.record((now += 10), 1);
    t.record((now += 50), 8);
    const s = t.summary();
    expect(s.p50IntervalMs).toBe(10);
    expect(s.p95IntervalMs).toBe(50);
    expect(s.p95CpuMs).toBe(8);
  });

  it('reports zeros until two frames exist and rejects a bad capacity', () => {
    const t = new FrameTimer();
    t.record(5, 1);
    expect(t.summary()).toMatchObject({ frames: 1, fps: 0 });
    expect(() => new FrameTimer(1)).toThrow(/capacity/);
  });
});
