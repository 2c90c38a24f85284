// Where a scene's content is, for the orbit camera to frame: the box around its bodies (moving ones where the view
// puts them, static ones by position and, unless huge like a ground plane, their extent), clipped to the scenario's
// bounds. Plain math on descriptors and views; no DOM, no GPU.
import type { SnapshotView } from '../../shared/protocol/snapshot-frame.ts';
import type { ShapeSpec } from '../../shared/physics-data/shape-spec.ts';
import type { BodyDescriptor } from '../../shared/sim/types.ts';

type Vec3 = [number, number, number];

/** Statics wider than this (m, half extent) count by their centre only: a ground plane says little about content. */
const HUGE_HALF_EXTENT_METRES = 15;

/** A rough half extent of a shape (m): enough to frame it, never used for physics. */
export function shapeHalfExtent(shape: ShapeSpec): number {
  switch (shape.kind) {
    case 'box':
      return Math.max(shape.halfExtents.x, shape.halfExtents.y, shape.halfExtents.z);
    case 'sphere':
      return shape.radius;
    case 'capsule':
      return shape.halfHeight + shape.radius;
    case 'cylinder':
      return Math.max(shape.halfHeight, shape.radius);
    default:
      return 0;
  }
}

/** The box around the scene's content (min, max corners), within `bounds`; at least 8 m a side. */
export function contentBox(statics: Iterable<BodyDescriptor>, view: SnapshotView | null, bounds: { min: { x: number; y: number; z: number }; max: { x: number; y: number; z: number } }): { min: Vec3; max: Vec3 } {
  const min: Vec3 = [Infinity, Infinity, Infinity];
  const max: Vec3 = [-Infinity, -Infinity, -Infinity];
  const lo: Vec3 = [bounds.min.x, bounds.min.y, bounds.min.z];
  const hi: Vec3 = [bounds.max.x, bounds.max.y, bounds.max.z];
  const add = (x: number, y: number, z: number, r: number): void => {
    const p: Vec3 = [x, y, z];
    for (let i = 0; i < 3; i++) {
      if (!Number.isFinite(p[i])) return;
    }
    for (let i = 0; i < 3; i++) {
      min[i] = Math.min(min[i], Math.max(lo[i], p[i] - r));
      max[i] = Math.max(max[i], Math.min(hi[i], p[i] + r));
    }
  };
  for (const d of statics) {
    if (d.hidden) continue;
    const r = shapeHalfExtent(d.shape);
    add(d.position.x, d.position.y, d.position.z, r > HUGE_HALF_EXTENT_METRES ? 0 : r);
  }
  if (view) for (let i = 0; i < view.ids.length; i++) add(view.positions[i * 3], view.positions[i * 3 + 1], view.positions[i * 3 + 2], 0.5);
  if (!(min[0] <= max[0])) return { min: lo, max: hi };
  for (let i = 0; i < 3; i++) {
    const pad = Math.max(0, 4 - (max[i] - min[i]) / 2);
    min[i] -= pad;
    max[i] += pad;
  }
  return { min, max };
}
