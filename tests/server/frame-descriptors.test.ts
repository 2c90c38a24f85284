// Tests for server/frame-descriptors.ts: a frame held back (durability tick) still describes the bodies it shows after
// they left the simulation, until the tick that removed them has been sent.
import { describe, expect, it } from 'vitest';
import { FrameDescriptors } from '../../server/frame-descriptors.ts';
import type { BodyDescriptor } from '../../shared/sim/types.ts';

const box = (id: number): BodyDescriptor => ({ id, motion: 'dynamic', shape: { kind: 'box', halfExtents: { x: id, y: 1, z: 1 } } }) as BodyDescriptor;

describe('FrameDescriptors', () => {
  it('keeps a captured body described until its removal is sent, skipping scene statics', () => {
    const live = new Map([1, 2, 3].map((id) => [id, box(id)]));
    const fd = new FrameDescriptors();
    fd.capture(Uint32Array.of(1, 2, 3), 3, (id) => id === 3, (id) => live.get(id));
    expect(fd.get(3)).toBeUndefined();
    // Tick t removes body 2; the frame of t − 1 (showing it) is sent after that.
    live.delete(2);
    const removals = fd.removals([2]);
    expect(fd.get(2)).toEqual(box(2));
    fd.release(removals); // tick t sent
    expect(fd.get(2)).toBeUndefined();
    expect(fd.get(1)).toEqual(box(1));
  });

  it('does not drop a descriptor that a new body with the same id brought in since', () => {
    const fd = new FrameDescriptors();
    fd.capture([7], 1, () => false, () => box(7));
    const removals = fd.removals([7]);
    fd.release([]);
    fd.release(removals);
    const again = { ...box(7), motion: 'kinematic' } as BodyDescriptor;
    fd.capture([7], 1, () => false, () => again);
    fd.release(removals);
    expect(fd.get(7)).toBe(again);
  });
});
