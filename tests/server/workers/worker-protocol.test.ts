// Tests for server/workers/worker-protocol.ts: a flush packs every member's bytes into one transferable buffer, a
// message shared by many members once, and unpacks to the same bytes, members and kinds in order.
import { describe, expect, it } from 'vitest';
import { DeliveryKind } from '../../../server/hosted-room.ts';
import { ByteBatcher, forEachSend } from '../../../server/workers/worker-protocol.ts';

describe('worker protocol byte batches', () => {
  it('packs a shared message once and hands every member its bytes in order', () => {
    const batcher = new ByteBatcher();
    expect(batcher.empty).toBe(true);
    const events = Uint8Array.of(1, 2, 3);
    const snapshotA = Uint8Array.of(9, 9);
    batcher.add(7, events, DeliveryKind.Reliable);
    batcher.add(8, events, DeliveryKind.Reliable);
    batcher.add(7, snapshotA, DeliveryKind.Snapshot);
    batcher.add(8, Uint8Array.of(4), DeliveryKind.Snapshot);
    const batch = batcher.take();
    expect(batch.buffer.byteLength).toBe(3 + 2 + 1);
    const got: Array<[number, number[], number]> = [];
    forEachSend(batch, (member, bytes, kind) => got.push([member, [...bytes], kind]));
    expect(got).toEqual([
      [7, [1, 2, 3], DeliveryKind.Reliable],
      [8, [1, 2, 3], DeliveryKind.Reliable],
      [7, [9, 9], DeliveryKind.Snapshot],
      [8, [4], DeliveryKind.Snapshot],
    ]);
    expect(batcher.empty).toBe(true);
  });

  it('starts each flush afresh: a message added again after a flush is packed in the new buffer', () => {
    const batcher = new ByteBatcher();
    const m = Uint8Array.of(5, 6);
    batcher.add(1, m, DeliveryKind.Reliable);
    const first = batcher.take();
    batcher.add(2, m, DeliveryKind.Reliable);
    const second = batcher.take();
    expect(second.buffer).not.toBe(first.buffer);
    const got: number[][] = [];
    forEachSend(second, (member, bytes) => got.push([member, ...bytes]));
    expect(got).toEqual([[2, 5, 6]]);
    expect(batcher.take().sends.length).toBe(0);
  });
});
