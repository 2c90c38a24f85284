// Tests for scenarios/lib/terrain-grid.ts: mesh sizes and winding, shared tile edges, the surface height of the
// triangulation, height-sample layout, and argument checks.
import { describe, expect, it } from 'vitest';
import { gridMesh, heightSamples, meshHeightAt } from '../../../scenarios/lib/terrain-grid.ts';

const wavy = (x: number, z: number): number => 0.3 * x - 0.2 * z + ((x * z) % 3);

describe('terrain-grid', () => {
  it('builds (cells + 1)² vertices and two upward-facing triangles per cell', () => {
    const m = gridMesh(wavy, -2, 3, 4, 5, 0.5);
    expect(m.positions).toHaveLength(5 * 6 * 3);
    expect(m.indices).toHaveLength(4 * 5 * 6);
    for (let t = 0; t < m.indices.length; t += 3) {
      const [a, b, c] = [m.indices[t] * 3, m.indices[t + 1] * 3, m.indices[t + 2] * 3];
      const e1 = [m.positions[b] - m.positions[a], m.positions[b + 1] - m.positions[a + 1], m.positions[b + 2] - m.positions[a + 2]];
      const e2 = [m.positions[c] - m.positions[a], m.positions[c + 1] - m.positions[a + 1], m.positions[c + 2] - m.positions[a + 2]];
      const ny = e1[2] * e2[0] - e1[0] * e2[2];
      expect(ny).toBeGreaterThan(0);
    }
    expect(m.positions.slice(0, 3)).toEqual([-1, wavy(-1, 1.5), 1.5]);
  });

  it('gives neighbouring tiles identical vertices along their shared edge', () => {
    const left = gridMesh(wavy, 0, 0, 4, 4, 0.7);
    const right = gridMesh(wavy, 4, 0, 4, 4, 0.7);
    for (let k = 0; k <= 4; k++) {
      const l = (k * 5 + 4) * 3;
      const r = k * 5 * 3;
      expect(right.positions.slice(r, r + 3)).toEqual(left.positions.slice(l, l + 3));
    }
  });

  it('reports the height of the triangulated surface, exact at vertices and linear inside a triangle', () => {
    const flatish = (x: number, z: number): number => (x === 1 && z === 1 ? 3 : 0);
    expect(meshHeightAt(flatish, 1, 1, 1)).toBe(3);
    expect(meshHeightAt(flatish, 0.5, 0.5, 1)).toBeCloseTo(0, 12); // on the diagonal (1,0)–(0,1), away from (1,1)
    expect(meshHeightAt(flatish, 0.75, 0.75, 1)).toBeCloseTo(1.5, 12);
    expect(meshHeightAt(wavy, 2, -3, 0.5)).toBeCloseTo(wavy(2, -3), 12);
  });

  it('lays height samples out row-major in z', () => {
    const h = heightSamples((x, z) => x + 10 * z, 1, 2, 3, 0.5);
    expect(h).toEqual([21, 21.5, 22, 26, 26.5, 27, 31, 31.5, 32]);
  });

  it('rejects bad grids and non-finite heights with clear Errors', () => {
    expect(() => gridMesh(wavy, 0.5, 0, 2, 2, 1)).toThrow(/lattice origin must be integers/);
    expect(() => gridMesh(wavy, 0, 0, 0, 2, 1)).toThrow(/cell counts must be positive integers/);
    expect(() => gridMesh(wavy, 0, 0, 2, 2, 0)).toThrow(/cellSizeMetres must be > 0/);
    expect(() => gridMesh(() => Number.NaN, 0, 0, 2, 2, 1)).toThrow(/is not finite/);
    expect(() => heightSamples(wavy, 0, 0, 1, 1)).toThrow(/sampleCount must be an integer >= 2/);
  });
});
