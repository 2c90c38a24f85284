// Tests for client/render/mesh-ground.ts: the surface height of static triangle meshes below a point, through each
// mesh's pose, picking the highest surface under the point and nothing outside the triangles.
import { describe, expect, it } from 'vitest';
import { MeshGround } from '../../../client/render/mesh-ground.ts';

const I = { x: 0, y: 0, z: 0, w: 1 };
// A 2×2-cell sloped patch over x, z ∈ [0, 4]: y = x / 4 (so y rises from 0 to 1 along x).
function slope(): { positions: number[]; indices: number[] } {
  const positions: number[] = [];
  for (let iz = 0; iz <= 2; iz++) for (let ix = 0; ix <= 2; ix++) positions.push(ix * 2, (ix * 2) / 4, iz * 2);
  const indices: number[] = [];
  for (let iz = 0; iz < 2; iz++)
    for (let ix = 0; ix < 2; ix++) {
      const a = iz * 3 + ix;
      indices.push(a, a + 3, a + 1, a + 1, a + 3, a + 4);
    }
  return { positions, indices };
}

describe('MeshGround', () => {
  it('gives the height of a sloped mesh between its vertices', () => {
    const g = new MeshGround([{ ...slope(), position: { x: 0, y: 0, z: 0 }, rotation: I }]);
    expect(g.size).toBe(8);
    expect(g.surfaceBelow(1, 10, 1)).toBeCloseTo(0.25, 9);
    expect(g.surfaceBelow(3.2, 10, 0.7)).toBeCloseTo(0.8, 9);
    expect(g.surfaceBelow(2, 10, 3.9)).toBeCloseTo(0.5, 9);
  });

  it('answers null outside the mesh and below its surface', () => {
    const g = new MeshGround([{ ...slope(), position: { x: 0, y: 0, z: 0 }, rotation: I }]);
    expect(g.surfaceBelow(-0.5, 10, 1)).toBeNull();
    expect(g.surfaceBelow(1, 10, 4.5)).toBeNull();
    // A point under the surface has no ground below it on this mesh.
    expect(g.surfaceBelow(3, 0.2, 1)).toBeNull();
  });

  it('moves the mesh by its position and rotation', () => {
    // A quarter turn about +y maps local (x, z) to world (z, −x); the slope then rises along −z.
    const s = Math.SQRT1_2;
    const g = new MeshGround([{ ...slope(), position: { x: 10, y: 2, z: 0 }, rotation: { x: 0, y: s, z: 0, w: s } }]);
    // Local (3, y, 1) lands at world (10 + 1, 2 + 0.75, −3).
    expect(g.surfaceBelow(11, 10, -3)).toBeCloseTo(2.75, 9);
    expect(g.surfaceBelow(1, 10, 1)).toBeNull();
  });

  it('takes the highest of stacked meshes that is still below the point', () => {
    const flat = (y: number) => ({ positions: [0, y, 0, 4, y, 0, 0, y, 4, 4, y, 4], indices: [0, 2, 1, 1, 2, 3], position: { x: 0, y: 0, z: 0 }, rotation: I });
    const g = new MeshGround([flat(0), flat(3), flat(6)]);
    expect(g.surfaceBelow(1, 10, 1)).toBe(6);
    expect(g.surfaceBelow(1, 5, 1)).toBe(3);
    expect(g.surfaceBelow(1, 2, 1)).toBe(0);
  });

  it('holds no triangles for no meshes and answers null', () => {
    const g = new MeshGround([]);
    expect(g.size).toBe(0);
    expect(g.surfaceBelow(0, 0, 0)).toBeNull();
  });
});
