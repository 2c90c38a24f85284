// Tests for server/input-buffer.ts: per-tick storage, repeat-last, late/too-far drops, redundancy, suspend/resume.
import { describe, expect, it } from 'vitest';
import { InputBuffer, OfferResult } from '../../server/input-buffer.ts';
import { NEUTRAL_INPUT, type InputCommand } from '../../shared/sim/input.ts';

const cmd = (moveX: number): InputCommand => ({ moveX, moveZ: 0, yaw: 0, pitch: 0, buttons: 0 });

describe('InputBuffer', () => {
  it('applies the command stamped for each tick', () => {
    const buf = new InputBuffer(10);
    expect(buf.offer(11, cmd(2))).toBe(OfferResult.Accepted);
    expect(buf.offer(10, cmd(1))).toBe(OfferResult.Accepted);
    expect(buf.take(10)).toEqual({ command: cmd(1), repeated: false });
    expect(buf.take(11)).toEqual({ command: cmd(2), repeated: false });
    expect(buf.size).toBe(0);
  });

  it('repeats the last applied command when none arrived, neutral before the first', () => {
    const buf = new InputBuffer(0);
    expect(buf.take(0)).toEqual({ command: NEUTRAL_INPUT, repeated: true });
    buf.offer(1, cmd(5));
    buf.take(1);
    expect(buf.take(2)).toEqual({ command: cmd(5), repeated: true });
    expect(buf.stats.repeated).toBe(2);
  });

  it('drops inputs for ticks already applied and counts them', () => {
    const buf = new InputBuffer(0);
    buf.take(0);
    buf.take(1);
    expect(buf.offer(1, cmd(9))).toBe(OfferResult.Late);
    expect(buf.stats.late).toBe(1);
    expect(buf.take(2).command).toEqual(NEUTRAL_INPUT);
  });

  it('counts a redundant copy of an applied input as a duplicate, not as late', () => {
    const buf = new InputBuffer(0);
    buf.offer(0, cmd(1));
    buf.take(0);
    buf.take(1); // nothing arrived for tick 1: repeated
    expect(buf.offer(0, cmd(1))).toBe(OfferResult.Duplicate);
    expect(buf.offer(1, cmd(2))).toBe(OfferResult.Late);
    expect(buf.stats).toMatchObject({ duplicates: 1, late: 1 });
  });

  it('keeps the first copy of a redundant input', () => {
    const buf = new InputBuffer(0);
    buf.offer(3, cmd(1));
    expect(buf.offer(3, cmd(2))).toBe(OfferResult.Duplicate);
    buf.take(0);
    buf.take(1);
    buf.take(2);
    expect(buf.take(3).command).toEqual(cmd(1));
  });

  it('stays bounded: inputs beyond the lead window are dropped', () => {
    const buf = new InputBuffer(0, 8);
    for (let t = 0; t < 1000; t++) buf.offer(t, cmd(1));
    expect(buf.size).toBe(9);
    expect(buf.stats.tooFar).toBe(991);
  });

  it('refuses to skip ticks', () => {
    const buf = new InputBuffer(5);
    expect(() => buf.take(6)).toThrow(/expected tick 5/);
  });

  it('applies the hold command while suspended, drops what was waiting, and takes new commands after resume', () => {
    const buf = new InputBuffer(0);
    buf.offer(0, cmd(50));
    buf.offer(1, cmd(60));
    buf.offer(2, cmd(70));
    expect(buf.take(0).command).toEqual(cmd(50));
    const hold = { ...NEUTRAL_INPUT, yaw: 1234 };
    buf.suspend(hold);
    expect(buf.size).toBe(0);
    expect(buf.take(1)).toEqual({ command: hold, repeated: false });
    expect(buf.take(2)).toEqual({ command: hold, repeated: false });
    expect(buf.stats).toMatchObject({ held: 2, repeated: 0 });
    buf.resume();
    buf.offer(4, cmd(-20));
    expect(buf.take(3)).toEqual({ command: hold, repeated: true });
    expect(buf.take(4)).toEqual({ command: cmd(-20), repeated: false });
  });
  it('goes on from its exported state exactly as the buffer it came from (a room moving threads)', () => {
    const a = new InputBuffer(0, 10);
    const c = (moveX: number) => ({ ...NEUTRAL_INPUT, moveX });
    a.offer(0, c(1));
    a.offer(3, c(3));
    a.take(0);
    a.take(1); // repeated
    const b = InputBuffer.fromState(structuredClone(a.exportState()));
    expect(b.offer(0, c(9))).toBe(OfferResult.Duplicate);
    expect(b.offer(1, c(9))).toBe(OfferResult.Late);
    expect(b.offer(13, c(9))).toBe(OfferResult.TooFar); // the window (10) counts from the next tick, 2
    expect(b.take(2)).toEqual({ command: c(1), repeated: true });
    expect(b.take(3)).toEqual({ command: c(3), repeated: false });
    expect(b.stats).toMatchObject({ accepted: 2, repeated: 2, duplicates: 1, late: 1, tooFar: 1 });
  });
});
