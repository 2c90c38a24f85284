// Tests of the renderer's instance bookkeeping: grouping by mesh, packing layout, static upload on change only,
// visibility, and mesh lifetime reporting.
import { describe, expect, it } from 'vitest';
import { InstanceStore, type BodyStyle } from '../../../client/render/instance-store.ts';
import { INSTANCE_FLOATS } from '../../../client/render/shaders.ts';
import { shapeMeshRef } from '../../../client/render/shape-mesh.ts';

const style = (color: [number, number, number] = [1, 0, 0]): BodyStyle => ({ color, emissive: 0, flags: 0, visible: true });
const box = shapeMeshRef({ kind: 'box', halfExtents: { x: 1, y: 2, z: 3 } });
const sphere = shapeMeshRef({ kind: 'sphere', radius: 0.5 });

describe('InstanceStore', () => {
  it('packs dynamic bodies grouped by mesh in contiguous runs, ordered by id', () => {
    const s = new InstanceStore();
    s.add(5, { mesh: box, isStatic: false, style: style() });
    s.add(2, { mesh: sphere, isStatic: false, style: style() });
    s.add(9, { mesh: box, isStatic: false, style: style() });
    s.add(1, { mesh: sphere, isStatic: false, style: style() });
    const packed = s.packDynamic();
    expect(packed.count).toBe(4);
    expect(packed.ranges).toEqual([
      { key: 'sphere', first: 0, count: 2 },
      { key: 'box', first: 2, count: 2 },
    ]);
  });

  it('writes position, flags, rotation, scale, emissive and colour into each instance', () => {
    const s = new InstanceStore();
    s.add(3, { mesh: box, isStatic: false, style: { color: [0.1, 0.2, 0.3], emissive: 0.5, flags: 2, visible: true } });
    s.setPose(3, 1, 2, 3, 0, 0.6, 0, 0.8);
    const { data } = s.packDynamic();
    expect(Array.from(data.subarray(0, INSTANCE_FLOATS)).map((v) => Math.round(v * 1e6) / 1e6)).toEqual([1, 2, 3, 2, 0, 0.6, 0, 0.8, 1, 2, 3, 0.5, 0.1, 0.2, 0.3, 1]);
  });

  it('reports static instances dirty only when a static body is added, moved, restyled or removed', () => {
    const s = new InstanceStore();
    s.add(0, { mesh: box, isStatic: true, style: style(), position: { x: 0, y: -1, z: 0 } });
    expect(s.takeStaticDirty()).toBe(true);
    expect(s.packStatic().count).toBe(1);
    expect(s.takeStaticDirty()).toBe(false);
    s.add(1, { mesh: sphere, isStatic: false, style: style() });
    s.setPose(1, 0, 5, 0, 0, 0, 0, 1);
    expect(s.takeStaticDirty()).toBe(false);
    s.setStyle(0, { emissive: 1 });
    expect(s.takeStaticDirty()).toBe(true);
    s.setStyle(0, { emissive: 1 });
    expect(s.takeStaticDirty()).toBe(false);
    s.remove(0);
    expect(s.takeStaticDirty()).toBe(true);
    expect(s.packStatic().count).toBe(0);
  });

  it('leaves invisible bodies out of the packed instances', () => {
    const s = new InstanceStore();
    s.add(0, { mesh: box, isStatic: false, style: style() });
    s.add(1, { mesh: box, isStatic: false, style: { ...style(), visible: false } });
    expect(s.packDynamic().count).toBe(1);
    s.setStyle(1, { visible: true });
    expect(s.packDynamic().count).toBe(2);
  });

  it('tells when a mesh gets its first user and when its last user leaves', () => {
    const s = new InstanceStore();
    expect(s.add(0, { mesh: box, isStatic: false, style: style() })).toBe(true);
    expect(s.add(1, { mesh: box, isStatic: false, style: style() })).toBe(false);
    expect(s.remove(0)).toBeNull();
    expect(s.remove(1)).toBe('box');
    expect(s.remove(1)).toBeNull();
    expect(s.size).toBe(0);
  });

  it('grows its packing buffer past the initial capacity', () => {
    const s = new InstanceStore();
    for (let i = 0; i < 1000; i++) {
      s.add(i, { mesh: sphere, isStatic: false, style: style() });
      s.setPose(i, i, 0, 0, 0, 0, 0, 1);
    }
    const packed = s.packDynamic();
    expect(packed.count).toBe(1000);
    expect(packed.data[999 * INSTANCE_FLOATS]).toBe(999);
  });

  it('rejects duplicate and invalid ids, leaving the store unchanged', () => {
    const s = new InstanceStore();
    s.add(4, { mesh: box, isStatic: false, style: style() });
    expect(() => s.add(4, { mesh: sphere, isStatic: false, style: style() })).toThrow(/body 4 is already registered/);
    expect(() => s.add(-1, { mesh: box, isStatic: false, style: style() })).toThrow(/non-negative integer/);
    expect(s.ids()).toEqual([4]);
    expect(s.packDynamic().ranges).toEqual([{ key: 'box', first: 0, count: 1 }]);
  });
});
