// Tests for server/workers/room-cost.ts: estimates before a room is measured, and where a new room is placed or why
// it is refused.
import { describe, expect, it } from 'vitest';
import { estimateTickCpuMs, placeRoom } from '../../../server/workers/room-cost.ts';

describe('room cost', () => {
  it('estimates a heavier room of a scenario as costlier, and an unknown scenario at a fixed cost', () => {
    expect(estimateTickCpuMs('shape-rain', { count: 4000 })).toBeGreaterThan(estimateTickCpuMs('shape-rain', {}));
    expect(estimateTickCpuMs('convex-hulls', { count: 2000 })).toBeGreaterThan(estimateTickCpuMs('convex-hulls', { count: 150 }));
    expect(estimateTickCpuMs('no-such-scene', {})).toBe(estimateTickCpuMs('another-unknown', { x: 5 }));
  });

  it('places a room on the worker with the most headroom when it fits', () => {
    const workers = [
      { worker: 0, rooms: 2, headroomMs: 3 },
      { worker: 1, rooms: 1, headroomMs: 9 },
      { worker: 2, rooms: 3, headroomMs: 1 },
    ];
    expect(placeRoom(workers, 5, 'shape-rain', 12.5)).toEqual({ worker: 1 });
  });

  it('gives a room heavier than any headroom a worker of its own when one is idle', () => {
    const workers = [
      { worker: 0, rooms: 1, headroomMs: 11 },
      { worker: 1, rooms: 0, headroomMs: 12.5 },
    ];
    expect(placeRoom(workers, 24, 'shape-rain', 12.5)).toEqual({ worker: 1 });
  });

  it('refuses a room no worker has headroom for, naming the scenario, its need and the best headroom', () => {
    const workers = [
      { worker: 0, rooms: 1, headroomMs: 4 },
      { worker: 1, rooms: 1, headroomMs: -10 },
    ];
    const placed = placeRoom(workers, 15.3, 'height-field', 12.5);
    expect(placed).toEqual({ refusal: expect.stringMatching(/^no capacity for another height-field room: it needs about 15\.3 ms .* left is 4\.0 ms \(of 12\.5 ms per tick on each of 2 workers\)$/) });
    expect(placeRoom([], 1, 'x', 12.5)).toEqual({ refusal: expect.stringMatching(/no room worker is running/) });
  });
});
