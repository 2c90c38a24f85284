// Tests of the body table: ids stay ascending whatever order bodies arrive in (checkpoint restores add old ids
// late), lookups by stable and Jolt id, sensor membership, and ownership of stale handles.
import { describe, expect, it } from 'vitest';
import type { BodyHandle } from '../../../shared/physics/index.ts';
import { BodyTable } from '../../../shared/physics/body-table.ts';

function handle(id: number, isSensor = false): BodyHandle {
  return { id, joltId: 1000 + id, isSensor, removed: false } as unknown as BodyHandle;
}

describe('body-table', () => {
  it('keeps ids ascending whatever order bodies are added and removed in', () => {
    const t = new BodyTable();
    const hs = [5, 1, 9, 3, 7, 2].map((id) => handle(id));
    hs.forEach((h) => t.add(h));
    expect(t.sortedIds).toEqual([1, 2, 3, 5, 7, 9]);
    t.delete(hs[0]);
    t.delete(hs[2]);
    expect(t.sortedIds).toEqual([1, 2, 3, 7]);
    t.add(handle(4));
    expect(t.sortedIds).toEqual([1, 2, 3, 4, 7]);
    expect(t.size).toBe(5);
  });

  it('finds bodies by stable id and by Jolt id, and knows the sensors', () => {
    const t = new BodyTable();
    const zone = handle(2, true);
    const ball = handle(3);
    t.add(zone);
    t.add(ball);
    expect(t.get(3)).toBe(ball);
    expect(t.byJoltId(1002)).toBe(zone);
    expect(t.isSensorJoltId(1002)).toBe(true);
    expect(t.isSensorJoltId(1003)).toBe(false);
    t.delete(zone);
    expect(t.byJoltId(1002)).toBeUndefined();
    expect(t.isSensorJoltId(1002)).toBe(false);
  });

  it('owns only the live handle it holds, not a stale one with the same id', () => {
    const t = new BodyTable();
    const old = handle(1);
    t.add(old);
    expect(t.owns(old)).toBe(true);
    t.delete(old);
    const again = handle(1);
    t.add(again);
    expect(t.owns(old)).toBe(false);
    expect(t.owns(again)).toBe(true);
    expect(t.owns(undefined)).toBe(false);
  });
});
