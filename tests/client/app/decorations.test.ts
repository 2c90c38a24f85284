// Tests for client/app/decorations.ts: a visor in front of each character along its yaw, a shadow on the static box
// below a moving body, and a spark where a bullet bounces; nothing for bodies over no box.
import { describe, expect, it } from 'vitest';
import { Decorations, footprintRadius, heightFieldSurfaceY, isBullet } from '../../../client/app/decorations.ts';
import { WorldView, type RenderTarget } from '../../../client/app/world-view.ts';
import { InstanceStore } from '../../../client/render/instance-store.ts';
import { shapeMeshRef } from '../../../client/render/shape-mesh.ts';
import type { SnapshotView } from '../../../shared/protocol/snapshot-frame.ts';
import type { BodyDescriptor, CharacterState } from '../../../shared/sim/types.ts';

function fakeRenderer(): RenderTarget & { store: InstanceStore } {
  const store = new InstanceStore();
  return {
    store,
    addBody(id, spec) {
      store.add(id, { mesh: shapeMeshRef(spec.shape, `body ${id}`), isStatic: spec.isStatic, style: { color: [1, 1, 1], emissive: 0, flags: 0, visible: true, ...spec.style }, position: spec.position, rotation: spec.rotation });
    },
    removeBody(id) {
      store.remove(id);
    },
  };
}

const I = { x: 0, y: 0, z: 0, w: 1 };
const ground: BodyDescriptor = { id: 1, shape: { kind: 'box', halfExtents: { x: 20, y: 0.5, z: 20 } }, color: [0.5, 0.5, 0.5], motion: 'static', hidden: false, position: { x: 0, y: -0.5, z: 0 }, rotation: I };
const crate: BodyDescriptor = { id: 2, shape: { kind: 'box', halfExtents: { x: 0.5, y: 0.5, z: 0.5 } }, color: [1, 0, 0], motion: 'dynamic', hidden: false, position: { x: 0, y: 5, z: 0 }, rotation: I };
const bullet: BodyDescriptor = { id: 3, shape: { kind: 'sphere', radius: 0.05 }, color: [1, 1, 0], motion: 'dynamic', hidden: false, position: { x: 0, y: 1, z: 0 }, rotation: I };

function view(bodies: Array<[number, number, number, number]>, characters: CharacterState[] = []): SnapshotView {
  return { ids: bodies.map((b) => b[0]), positions: Float64Array.from(bodies.flatMap((b) => [b[1], b[2], b[3]])), rotations: Float64Array.from(bodies.flatMap(() => [0, 0, 0, 1])), characters } as unknown as SnapshotView;
}

describe('decorations', () => {
  it('tells bullets from other bodies and sizes shadows by footprint', () => {
    expect(isBullet(bullet)).toBe(true);
    expect(isBullet(crate)).toBe(false);
    expect(footprintRadius({ kind: 'sphere', radius: 0.4 })).toBe(0.4);
    expect(footprintRadius({ kind: 'mesh', positions: [], indices: [] })).toBe(0);
  });

  it('puts a visor in front of each character along its yaw and a shadow on the box below a moving body', () => {
    const r = fakeRenderer();
    const world = new WorldView(r, () => undefined);
    world.reset([ground], [crate]);
    const d = new Decorations(r, world);
    const hero = { playerId: 4, bodyId: 9, position: { x: 2, y: 0, z: 0 }, velocity: { x: 0, y: 0, z: 0 }, yaw: Math.PI / 2, pitch: 0, groundState: 'ground', buttons: 0 } as CharacterState;
    d.update(view([[2, 0, 5, 0]], [hero]), 0);
    const poses = r.store.ids().filter((id) => id >= 2 ** 40).map((id) => r.store.pose(id)!);
    // Yaw π/2 faces −X: the visor sits in front of the character on that side, at head height.
    const visor = poses.find((p) => p[1] > 1)!;
    expect(visor[0]).toBeCloseTo(2 - 0.3, 6);
    expect(visor[1]).toBeCloseTo(1.45, 6);
    // The crate's shadow lies on the ground's top face under it.
    const shadow = poses.find((p) => p[1] < 0.1)!;
    expect(shadow[0]).toBeCloseTo(0, 6);
    expect(shadow[1]).toBeGreaterThan(0);
    expect(shadow[1]).toBeLessThan(0.05);
    // The character leaves: its visor goes; the crate moves beyond the ground: its shadow hides.
    d.update(view([[2, 50, 5, 50]]), 16);
    const left = r.store.ids().filter((id) => id >= 2 ** 40);
    expect(left).toHaveLength(1);
    expect(r.store.style(left[0])!.visible).toBe(false);
  });

  it('sparks where a bullet turns sharply, and the spark fades away', () => {
    const r = fakeRenderer();
    const world = new WorldView(r, () => undefined);
    world.reset([ground], [bullet]);
    const d = new Decorations(r, world);
    d.update(view([[3, 0, 1, 0]]), 0);
    d.update(view([[3, 1, 1, 0]]), 16);
    d.update(view([[3, 2, 1, 0]]), 32);
    expect(r.store.ids().filter((id) => id >= 3 * 2 ** 40)).toHaveLength(0);
    d.update(view([[3, 1, 1, 0]]), 48); // bounced back
    const sparks = r.store.ids().filter((id) => id >= 3 * 2 ** 40);
    expect(sparks).toHaveLength(1);
    expect(r.store.pose(sparks[0])!.slice(0, 3)).toEqual([2, 1, 0]);
    d.update(view([[3, 0, 1, 0]]), 1000);
    expect(r.store.ids().filter((id) => id >= 3 * 2 ** 40)).toHaveLength(0);
  });

  it('finds the surface of a height field under a point, between its samples', () => {
    const hf: BodyDescriptor = { id: 7, shape: { kind: 'heightField', heights: [0, 2, 0, 2], sampleCount: 2, cellSize: 4, originXz: { x: -2, z: -2 } }, color: [1, 1, 1], motion: 'static', hidden: false, position: { x: 10, y: 1, z: 0 }, rotation: I };
    expect(heightFieldSurfaceY(hf, 8, -2)).toBeCloseTo(1, 9);
    expect(heightFieldSurfaceY(hf, 12, 2)).toBeCloseTo(3, 9);
    expect(heightFieldSurfaceY(hf, 10, 0)).toBeCloseTo(2, 9);
    expect(heightFieldSurfaceY(hf, 20, 0)).toBeNull();
    expect(heightFieldSurfaceY(crate, 0, 0)).toBeNull();
  });

  it('lays the shadow of a body in the air on the triangle-mesh terrain below it', () => {
    const r = fakeRenderer();
    const world = new WorldView(r, () => undefined);
    // One triangle pair over x, z ∈ [−5, 5], sloping up along x: y = 1 + x / 10.
    const terrain: BodyDescriptor = { id: 8, shape: { kind: 'mesh', positions: [-5, 0.5, -5, 5, 1.5, -5, -5, 0.5, 5, 5, 1.5, 5], indices: [0, 2, 1, 1, 2, 3] }, color: [0.4, 0.6, 0.4], motion: 'static', hidden: false, position: { x: 0, y: 0, z: 0 }, rotation: I };
    world.reset([terrain], [crate]);
    const d = new Decorations(r, world);
    d.update(view([[2, 3, 6, 1]]), 0);
    const shadows = r.store.ids().filter((id) => id >= 2 * 2 ** 40 && id < 3 * 2 ** 40);
    expect(shadows).toHaveLength(1);
    const pose = r.store.pose(shadows[0])!;
    expect(pose[0]).toBeCloseTo(3, 6);
    expect(pose[1]).toBeGreaterThan(1.3);
    expect(pose[1]).toBeLessThan(1.35);
  });
});
