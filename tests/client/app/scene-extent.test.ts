// Tests for client/app/scene-extent.ts: the orbit camera frames the scene's content, not its whole bounds.
import { describe, expect, it } from 'vitest';
import { contentBox } from '../../../client/app/scene-extent.ts';
import type { SnapshotView } from '../../../shared/protocol/snapshot-frame.ts';
import type { BodyDescriptor } from '../../../shared/sim/types.ts';

const bounds = { min: { x: -150, y: -10, z: -150 }, max: { x: 150, y: 140, z: 150 } };
const I = { x: 0, y: 0, z: 0, w: 1 };
const box = (id: number, x: number, y: number, z: number, half: number): BodyDescriptor => ({ id, shape: { kind: 'box', halfExtents: { x: half, y: half, z: half } }, color: [1, 1, 1], motion: 'static', hidden: false, position: { x, y, z }, rotation: I });

describe('scene-extent', () => {
  it('spans the static bodies and the moving ones, a huge ground counting by its centre only', () => {
    const statics = [box(1, 0, -0.5, 0, 100), box(2, 10, 1, 0, 1)];
    const view = { ids: [5], positions: Float64Array.of(-6, 3, 4) } as unknown as SnapshotView;
    const { min, max } = contentBox(statics, view, bounds);
    expect(min[0]).toBeCloseTo(-6.5, 6);
    expect(max[0]).toBeCloseTo(11, 6);
    expect(max[2] - min[2]).toBeGreaterThanOrEqual(8);
    expect(max[0] - min[0]).toBeLessThan(40);
  });

  it('ignores hidden volumes and non-finite positions, and falls back to the bounds when nothing is left', () => {
    const hidden = { ...box(3, 50, 0, 50, 1), hidden: true };
    const view = { ids: [9], positions: Float64Array.of(NaN, 0, 0) } as unknown as SnapshotView;
    expect(contentBox([hidden], view, bounds)).toEqual({ min: [-150, -10, -150], max: [150, 140, 150] });
  });
});
