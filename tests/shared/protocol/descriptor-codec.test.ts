// Tests of body descriptors on the wire: every shape kind round-trips, shared shapes are sent once, and malformed
// data fails with an error naming the row and field.
import { describe, expect, it } from 'vitest';
import { packValue, unpackFrame } from '../../../shared/protocol/codec.ts';
import { packDescriptors, parseShape, unpackDescriptors } from '../../../shared/protocol/descriptor-codec.ts';
import type { ShapeSpec } from '../../../shared/physics-data/shape-spec.ts';
import type { BodyDescriptor } from '../../../shared/sim/types.ts';

function body(id: number, shape: ShapeSpec, extra: Partial<BodyDescriptor> = {}): BodyDescriptor {
  return { id, shape, color: [0.1, 0.5, 0.9], motion: 'dynamic', hidden: false, position: { x: 1, y: 2.5, z: -3 }, rotation: { x: 0, y: 0.6, z: 0, w: 0.8 }, ...extra };
}

function viaWire(list: BodyDescriptor[]): BodyDescriptor[] {
  return unpackDescriptors(unpackFrame(packValue(packDescriptors(list))));
}

const allShapes: ShapeSpec[] = [
  { kind: 'box', halfExtents: { x: 1, y: 0.5, z: 2 } },
  { kind: 'sphere', radius: 0.3 },
  { kind: 'capsule', halfHeight: 0.9, radius: 0.4 },
  { kind: 'cylinder', halfHeight: 1, radius: 0.25 },
  { kind: 'convexHull', points: new Float32Array([0, 0, 0, 1, 0, 0, 0, 1, 0, 0, 0, 1]) },
  { kind: 'mesh', positions: [0, 0, 0, 1, 0, 0, 0, 0, 1], indices: new Uint32Array([0, 1, 2]) },
  { kind: 'heightField', heights: [0, 1, 2, 3], sampleCount: 2, cellSize: 0.5, originXz: { x: -1, z: -1 } },
  { kind: 'compound', parts: [{ shape: { kind: 'sphere', radius: 1 }, position: { x: 0, y: 1, z: 0 } }, { shape: { kind: 'box', halfExtents: { x: 1, y: 1, z: 1 } }, rotation: { x: 0, y: 0, z: 0, w: 1 } }] },
];

describe('descriptor-codec', () => {
  it('round-trips every shape kind with colour, motion, visibility, player and pose', () => {
    const list = allShapes.map((s, i) => body(i, s, i === 2 ? { playerId: 7, motion: 'kinematic' } : i === 6 ? { motion: 'static', hidden: true } : {}));
    const back = viaWire(list);
    expect(back).toHaveLength(list.length);
    back.forEach((d, i) => {
      const want = list[i];
      expect(d.id).toBe(want.id);
      expect(d.color).toEqual(want.color);
      expect(d.motion).toBe(want.motion);
      expect(d.hidden).toBe(want.hidden);
      expect(d.playerId).toBe(want.playerId);
      expect(d.position).toEqual(want.position);
      expect(d.rotation).toEqual(want.rotation);
      expect(JSON.stringify(d.shape)).toBe(JSON.stringify(toPlain(want.shape)));
    });
  });

  it('sends a shape shared by many bodies once', () => {
    const cube: ShapeSpec = { kind: 'box', halfExtents: { x: 0.5, y: 0.5, z: 0.5 } };
    const list = Array.from({ length: 900 }, (_, i) => body(i, { kind: 'box', halfExtents: { ...cube.halfExtents } }));
    const packed = packDescriptors(list);
    expect(packed[0]).toHaveLength(1);
    const back = viaWire(list);
    // Unpacked bodies share one ShapeSpec object, so a renderer can key meshes by identity.
    expect(back[0].shape).toBe(back[899].shape);
    expect(packValue(packed).length).toBeLessThan(900 * 120);
  });

  it('rejects malformed rows and shapes with the path of the bad field', () => {
    const good = packDescriptors([body(1, { kind: 'sphere', radius: 1 })]);
    expect(() => unpackDescriptors('nope')).toThrow(/\[shapes, rows\]/);
    expect(() => unpackDescriptors([good[0], [[1, 2]]])).toThrow(/rows\[0\]: must be an array of 15/);
    const badIndex = structuredClone(good);
    badIndex[1][0][1] = 5;
    expect(() => unpackDescriptors(badIndex)).toThrow(/rows\[0\]\.shape: index 5/);
    const nan = structuredClone(good);
    nan[1][0][9] = Number.NaN;
    expect(() => unpackDescriptors(nan)).toThrow(/rows\[0\]\[9\]: must be a finite number/);
    expect(() => unpackDescriptors([[{ kind: 'teapot' }], []])).toThrow(/shapes\[0\]\.kind: unknown shape kind "teapot"/);
  });

  it('checks shape fields: sizes, index ranges, sample counts and nesting depth', () => {
    expect(() => parseShape({ kind: 'box', halfExtents: { x: 1, y: 0, z: 1 } })).toThrow(/> 0/);
    expect(() => parseShape({ kind: 'mesh', positions: [0, 0, 0, 1, 1, 1, 2, 2, 2], indices: [0, 1, 3] })).toThrow(/indices\[2\]/);
    expect(() => parseShape({ kind: 'heightField', heights: [1, 2, 3], sampleCount: 2, cellSize: 1 })).toThrow(/needs 4 samples/);
    expect(() => parseShape({ kind: 'convexHull', points: [0, 0, 0] })).toThrow(/at least 3 points/);
    let deep: unknown = { kind: 'sphere', radius: 1 };
    for (let i = 0; i < 6; i++) deep = { kind: 'compound', parts: [{ shape: deep }] };
    expect(() => parseShape(deep)).toThrow(/nest deeper/);
  });
});

function toPlain(s: ShapeSpec): unknown {
  return JSON.parse(JSON.stringify(s, (_k, v) => (ArrayBuffer.isView(v) ? Array.from(v as unknown as ArrayLike<number>) : v)));
}
