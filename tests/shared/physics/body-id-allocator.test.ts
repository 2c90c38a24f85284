// Tests of the deterministic Jolt BodyID allocator: packing, reuse order, sequence numbers, claim and save/restore.
import { describe, expect, it } from 'vitest';
import { BodyIdAllocator, joltBodyIndex, joltBodySequence, packJoltBodyId } from '../../../shared/physics/body-id-allocator.ts';

describe('body-id-allocator', () => {
  it('packs index and sequence the way Jolt does (sequence in bits 23..30)', () => {
    expect(packJoltBodyId(0, 1)).toBe(0x800000);
    expect(packJoltBodyId(10, 6)).toBe(0x300000a);
    expect(packJoltBodyId(5, 255)).toBe(0x7f800005);
    expect(joltBodyIndex(0x300000a)).toBe(10);
    expect(joltBodySequence(0x300000a)).toBe(6);
  });

  it('hands out fresh indices first, then reuses freed ones last-in first-out with a new sequence number', () => {
    const a = new BodyIdAllocator(8);
    const ids = [a.allocate(), a.allocate(), a.allocate()];
    expect(ids.map(joltBodyIndex)).toEqual([0, 1, 2]);
    expect(ids.map(joltBodySequence)).toEqual([1, 1, 1]);
    a.release(ids[0]);
    a.release(ids[2]);
    const again = a.allocate();
    expect(joltBodyIndex(again)).toBe(2);
    expect(joltBodySequence(again)).toBe(2);
    expect(joltBodyIndex(a.allocate())).toBe(0);
  });

  it('wraps sequence numbers after 255', () => {
    const a = new BodyIdAllocator(1);
    let id = 0;
    for (let i = 0; i < 256; i++) {
      id = a.allocate();
      a.release(id);
    }
    expect(joltBodySequence(id)).toBe(0);
  });

  it('throws a clear error when every slot is in use', () => {
    const a = new BodyIdAllocator(2);
    a.allocate();
    a.allocate();
    expect(() => a.allocate()).toThrow(/all 2 body slots are in use/);
  });

  it('claims a specific id and refuses one already in use', () => {
    const a = new BodyIdAllocator(8);
    a.claim(packJoltBodyId(5, 9));
    expect(a.isLive(5)).toBe(true);
    expect(() => a.claim(packJoltBodyId(5, 10))).toThrow(/already in use/);
    expect(joltBodyIndex(a.allocate())).toBe(0);
  });

  it('restores a saved state so the same ids come out again', () => {
    const a = new BodyIdAllocator(16);
    const first = [a.allocate(), a.allocate(), a.allocate()];
    a.release(first[1]);
    const saved = a.save();
    const live = [0, 2];
    const branchA = [a.allocate(), a.allocate()];
    a.restore(saved, live);
    const branchB = [a.allocate(), a.allocate()];
    expect(branchB).toEqual(branchA);
  });

  it('rejects a corrupt saved state', () => {
    const a = new BodyIdAllocator(4);
    expect(() => a.restore({ highWater: 9, free: [], sequences: new Uint8Array(9) }, [])).toThrow(/bad state/);
    expect(() => a.restore({ highWater: 2, free: [3], sequences: new Uint8Array(2) }, [])).toThrow(/out of range/);
  });
});
