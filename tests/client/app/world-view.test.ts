// Tests of the world view: descriptors become drawn bodies, views place and show/hide them, and spawns, removals,
// reused ids and sensor events take effect at their tick.
import { describe, expect, it, vi } from 'vitest';
import { WorldView, scenarioEventText, type RenderTarget } from '../../../client/app/world-view.ts';
import { InstanceStore } from '../../../client/render/instance-store.ts';
import { InstanceFlag } from '../../../client/render/shaders.ts';
import { shapeMeshRef } from '../../../client/render/shape-mesh.ts';
import type { SnapshotView } from '../../../shared/protocol/snapshot-frame.ts';
import type { BodyDescriptor } from '../../../shared/sim/types.ts';

/** A renderer stand-in with the real instance store (no GPU). */
function fakeRenderer(): RenderTarget & { removed: number[] } {
  const store = new InstanceStore();
  const removed: number[] = [];
  return {
    store,
    removed,
    addBody(id, spec) {
      // Like Renderer.addBody: the mesh is built (and may throw) before the body is registered.
      const mesh = shapeMeshRef(spec.shape, `body ${id}`);
      mesh.build();
      store.add(id, { mesh, isStatic: spec.isStatic, style: { color: [1, 1, 1], emissive: 0, flags: 0, visible: true, ...spec.style }, position: spec.position, rotation: spec.rotation });
    },
    removeBody(id) {
      removed.push(id);
      store.remove(id);
    },
  };
}

const Q = { x: 0, y: 0, z: 0, w: 1 };
const ground: BodyDescriptor = { id: 0, shape: { kind: 'box', halfExtents: { x: 10, y: 0.5, z: 10 } }, color: [0.3, 0.4, 0.3], motion: 'static', hidden: false, position: { x: 0, y: -0.5, z: 0 }, rotation: Q };
const trigger: BodyDescriptor = { id: 1, shape: { kind: 'box', halfExtents: { x: 1, y: 1, z: 1 } }, color: [1, 0.9, 0.2], motion: 'static', hidden: true, position: { x: 3, y: 1, z: 0 }, rotation: Q };
const crate = (id: number, radius = 0.5): BodyDescriptor => ({ id, shape: { kind: 'sphere', radius }, color: [0.9, 0.3, 0.2], motion: 'dynamic', hidden: false, position: { x: 0, y: 5, z: 0 }, rotation: Q });

function view(tick: number, bodies: Array<[number, number, number, number]>): SnapshotView {
  return {
    tick,
    ids: Uint32Array.from(bodies.map((b) => b[0])),
    positions: Float32Array.from(bodies.flatMap((b) => [b[1], b[2], b[3]])),
    rotations: Float32Array.from(bodies.flatMap(() => [0, 0, 0, 1])),
    atRest: new Uint8Array(bodies.length),
    characters: [],
  };
}

describe('WorldView', () => {
  it('draws static bodies with the grid, hidden sensors as outlines, and moving bodies only once a view has them', () => {
    const r = fakeRenderer();
    const w = new WorldView(r, () => undefined);
    w.reset([ground, trigger], [crate(5)]);
    expect(r.store.style(0)).toMatchObject({ visible: true, flags: InstanceFlag.Grid });
    expect(r.store.style(1)).toMatchObject({ visible: true, flags: InstanceFlag.Outline });
    expect(r.store.style(5)?.visible).toBe(false);
    w.apply(view(10, [[5, 1, 2, 3]]), 10);
    expect(r.store.style(5)?.visible).toBe(true);
    expect(r.store.pose(5)?.slice(0, 3)).toEqual([1, 2, 3]);
    expect(w.drawnCount).toBe(3);
    w.apply(view(11, []), 11);
    expect(r.store.style(5)?.visible).toBe(false);
    expect(w.sensors()).toEqual([{ sensorId: 1, occupied: false, lit: false }]);
  });

  it('lights a sensor while something is inside, from the tick of the enter event to the tick of the exit', () => {
    const r = fakeRenderer();
    const lines: string[] = [];
    const w = new WorldView(r, (l) => lines.push(l));
    w.reset([ground, trigger], []);
    w.queueEvents([
      { type: 'sensorEnter', tick: 20, sensorId: 1, bodyId: 7, playerId: 2 },
      { type: 'sensorExit', tick: 30, sensorId: 1, bodyId: 7, playerId: 2 },
    ]);
    w.apply(null, 19.5);
    expect(r.store.style(1)?.emissive).toBe(0);
    const dim = r.store.style(1)!.color;
    expect(dim[0]).toBeLessThan(trigger.color[0]);
    w.apply(null, 20);
    expect(r.store.style(1)?.emissive).toBeGreaterThan(0);
    expect(r.store.style(1)?.color).toEqual(trigger.color);
    expect(w.sensors()).toEqual([{ sensorId: 1, occupied: true, lit: true }]);
    w.apply(null, 29.9);
    expect(r.store.style(1)?.emissive).toBeGreaterThan(0);
    w.apply(null, 30);
    expect(r.store.style(1)?.emissive).toBe(0);
    expect(r.store.style(1)?.color).toEqual(dim);
    expect(lines).toEqual(['player #2 entered zone 1', 'player #2 left zone 1']);
  });

  it('removes a body when the render time reaches its removal tick', () => {
    const r = fakeRenderer();
    const w = new WorldView(r, () => undefined);
    w.reset([ground], [crate(5)]);
    w.queueEvents([{ type: 'bodyRemoved', tick: 40, bodyId: 5 }]);
    w.apply(view(39, [[5, 0, 1, 0]]), 39);
    expect(r.store.has(5)).toBe(true);
    w.apply(view(40, []), 40);
    expect(r.store.has(5)).toBe(false);
    expect(r.removed).toEqual([5]);
  });

  it('registers spawns at once but swaps a reused id to its new body only at the tick that brought it', () => {
    const r = fakeRenderer();
    const w = new WorldView(r, () => undefined);
    w.reset([ground], [crate(5)]);
    w.addDescriptors(50, [crate(6), crate(5)]); // 6 is new; 5 repeated unchanged
    expect(r.store.has(6)).toBe(true);
    expect(r.removed).toEqual([]);
    w.addDescriptors(60, [{ ...crate(5), shape: { kind: 'box', halfExtents: { x: 1, y: 1, z: 1 } } }]);
    w.apply(view(59, [[5, 0, 1, 0]]), 59);
    expect(w.descriptor(5)?.shape.kind).toBe('sphere');
    w.apply(view(60, [[5, 0, 1, 0]]), 60);
    expect(w.descriptor(5)?.shape.kind).toBe('box');
    expect(r.removed).toEqual([5]);
    expect(r.store.style(5)?.visible).toBe(true);
  });

  it('shows a static body streamed in after the scene was built only while snapshots carry it', () => {
    const r = fakeRenderer();
    const w = new WorldView(r, () => undefined);
    w.reset([ground], []);
    const tile: BodyDescriptor = { id: 12, shape: { kind: 'box', halfExtents: { x: 4, y: 0.5, z: 4 } }, color: [0.4, 0.5, 0.3], motion: 'static', hidden: false, position: { x: 20, y: -0.5, z: 0 }, rotation: Q };
    w.addDescriptors(100, [tile]);
    expect(r.store.style(12)).toMatchObject({ visible: false, flags: InstanceFlag.Grid });
    w.apply(view(99, []), 99);
    expect(r.store.style(12)?.visible).toBe(false);
    w.apply(view(100, [[12, 20, -0.5, 0]]), 100);
    expect(r.store.style(12)?.visible).toBe(true);
    expect(r.store.pose(12)?.slice(0, 3)).toEqual([20, -0.5, 0]);
    expect(w.drawnCount).toBe(2);
    w.queueEvents([{ type: 'bodyRemoved', tick: 150, bodyId: 12 }]);
    w.apply(view(150, []), 150);
    expect(r.store.has(12)).toBe(false);
  });

  it('skips a body whose shape cannot be drawn instead of failing the whole world', () => {
    const r = fakeRenderer();
    const warn = vi.spyOn(console, 'warn').mockImplementation(() => undefined);
    const w = new WorldView(r, () => undefined);
    const flat: BodyDescriptor = { ...crate(9), shape: { kind: 'convexHull', points: [0, 0, 0, 1, 0, 0, 0, 1, 0, 1, 1, 0] } };
    w.reset([ground], [flat, crate(10)]);
    w.apply(view(1, [[9, 0, 0, 0], [10, 0, 0, 0]]), 1);
    expect(r.store.has(9)).toBe(false);
    expect(r.store.style(10)?.visible).toBe(true);
    expect(warn).toHaveBeenCalledWith(expect.stringMatching(/not drawing body 9: .*coplanar/));
    warn.mockRestore();
  });

  it('logs joins, leaves and scenario events in readable words', () => {
    const r = fakeRenderer();
    const lines: string[] = [];
    const w = new WorldView(r, (l) => lines.push(l));
    w.reset([ground], []);
    w.queueEvents([
      { type: 'scenario', tick: 3, name: 'door', value: 1 },
      { type: 'playerJoined', tick: 1, playerId: 4, name: 'ada' },
      { type: 'playerLeft', tick: 5, playerId: 4 },
    ]);
    w.apply(null, 10);
    expect(lines).toEqual(['ada (#4) joined', 'door opened', 'player #4 left']);
    expect(scenarioEventText('targetHit', 2)).toBe('targetHit: 2');
  });
});
