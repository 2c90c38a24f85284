// Tests for server/monitor/link-stats.ts: RTT from snapshot to ack (smoothed), input lead, unknown acks ignored, and
// the tick read from a framed snapshot message.
import { describe, expect, it } from 'vitest';
import { LinkStats, snapshotTick } from '../../../server/monitor/link-stats.ts';
import { encodeServerMessage } from '../../../shared/protocol/codec.ts';
import { createSnapshotFormat } from '../../../shared/protocol/quantization.ts';
import { encodeSnapshot } from '../../../shared/protocol/snapshot-codec.ts';
import { emptyFrame } from '../../../shared/protocol/snapshot-frame.ts';

describe('link-stats', () => {
  it('measures the round trip from a snapshot to its ack and smooths later samples', () => {
    const l = new LinkStats();
    l.snapshotSent(10, 1000);
    l.acked(10, 1040);
    expect(l.rttMs).toBe(40);
    l.snapshotSent(12, 2000);
    l.acked(12, 2120);
    expect(l.rttMs).toBe(50);
  });

  it('ignores acks of ticks it never sent, repeated acks and hostile values', () => {
    const l = new LinkStats();
    l.snapshotSent(5, 0);
    l.acked(6, 10);
    l.acked(-1, 10);
    l.acked(1.5, 10);
    expect(l.rttMs).toBeNull();
    l.acked(5, 30);
    l.acked(5, 900);
    expect(l.rttMs).toBe(30);
  });

  it('keeps the lead of the newest input over the room tick', () => {
    const l = new LinkStats();
    expect(l.inputLeadTicks).toBeNull();
    l.inputArrived(105, 100);
    expect(l.inputLeadTicks).toBe(5);
  });
});

describe('snapshotTick', () => {
  it('reads the tick of a framed snapshot message and refuses anything else', () => {
    const format = createSnapshotFormat({ min: { x: -10, y: -10, z: -10 }, max: { x: 10, y: 10, z: 10 } });
    const frame = encodeSnapshot(format, emptyFrame(123_456), null);
    const message = encodeServerMessage({ type: 'snapshot', bytes: frame, descriptors: [] });
    expect(snapshotTick(message, null)).toBe(123_456);
    expect(snapshotTick(encodeServerMessage({ type: 'pong', clientTimeMs: 1, serverTick: 5, serverTimeMs: 2, missedInputTicks: 0, roomTicksPerSecond: 60, roomSlow: false }), null)).toBeNull();
    expect(snapshotTick(new Uint8Array(0), null)).toBeNull();
    expect(snapshotTick(message.subarray(0, 2), null)).toBeNull();
  });

  it('completes the 16-bit tick of a delta snapshot from the previous snapshot tick', () => {
    const format = createSnapshotFormat({ min: { x: -10, y: -10, z: -10 }, max: { x: 10, y: 10, z: 10 } });
    const tick = 3 * 65536 + 7;
    const delta = encodeSnapshot(format, emptyFrame(tick), emptyFrame(tick - 5));
    const message = encodeServerMessage({ type: 'snapshot', bytes: delta, descriptors: [] });
    expect(snapshotTick(message, tick - 1)).toBe(tick);
    expect(snapshotTick(message, null)).toBeNull();
  });
});
