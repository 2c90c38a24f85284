// Terrain geometry from a height function: triangle meshes over lattice cells and height-field sample grids.
// Vertices sit on the global lattice (x = i·cellSize), so neighbouring tiles share their edge vertices exactly.

/** A height function: terrain height (m) at world (x, z). */
export type HeightFn = (xMetres: number, zMetres: number) => number;

/** A triangle soup in world coordinates (flat x,y,z and index triples), ready for a 'mesh' ShapeSpec. */
export interface GridMesh {
  positions: number[];
  indices: number[];
}

/**
 * The mesh of `heightAt` over lattice cells [i0, i0 + cellsX) × [k0, k0 + cellsZ) of `cellSizeMetres`, two
 * upward-facing (counter-clockwise seen from above +y) triangles per cell.
 */
export function gridMesh(heightAt: HeightFn, i0: number, k0: number, cellsX: number, cellsZ: number, cellSizeMetres: number): GridMesh {
  if (![i0, k0].every(Number.isInteger)) throw new Error(`gridMesh: lattice origin must be integers, got (${i0}, ${k0})`);
  if (!Number.isInteger(cellsX) || !Number.isInteger(cellsZ) || cellsX < 1 || cellsZ < 1) {
    throw new Error(`gridMesh: cell counts must be positive integers, got ${cellsX} × ${cellsZ}`);
  }
  if (!(cellSizeMetres > 0) || !Number.isFinite(cellSizeMetres)) throw new Error(`gridMesh: cellSizeMetres must be > 0, got ${cellSizeMetres}`);
  const vx = cellsX + 1;
  const vz = cellsZ + 1;
  const positions = new Array<number>(vx * vz * 3);
  let p = 0;
  for (let k = 0; k < vz; k++) {
    const z = (k0 + k) * cellSizeMetres;
    for (let i = 0; i < vx; i++) {
      const x = (i0 + i) * cellSizeMetres;
      const y = heightAt(x, z);
      if (!Number.isFinite(y)) throw new Error(`gridMesh: height at (${x}, ${z}) is not finite (${y})`);
      positions[p++] = x;
      positions[p++] = y;
      positions[p++] = z;
    }
  }
  const indices = new Array<number>(cellsX * cellsZ * 6);
  let t = 0;
  for (let k = 0; k < cellsZ; k++) {
    for (let i = 0; i < cellsX; i++) {
      const a = k * vx + i; // (i, k)
      const b = a + 1; // (i + 1, k)
      const c = a + vx; // (i, k + 1)
      const d = c + 1; // (i + 1, k + 1)
      indices[t++] = a;
      indices[t++] = c;
      indices[t++] = b;
      indices[t++] = b;
      indices[t++] = c;
      indices[t++] = d;
    }
  }
  return { positions, indices };
}

/** sampleCount² heights of `heightAt` on the lattice starting at world (x0, z0), row-major in z (index z·n + x). */
export function heightSamples(heightAt: HeightFn, x0: number, z0: number, sampleCount: number, cellSizeMetres: number): number[] {
  if (!Number.isInteger(sampleCount) || sampleCount < 2) throw new Error(`heightSamples: sampleCount must be an integer >= 2, got ${sampleCount}`);
  const out = new Array<number>(sampleCount * sampleCount);
  for (let k = 0; k < sampleCount; k++) {
    const z = z0 + k * cellSizeMetres;
    for (let i = 0; i < sampleCount; i++) {
      const y = heightAt(x0 + i * cellSizeMetres, z);
      if (!Number.isFinite(y)) throw new Error(`heightSamples: height at sample (${i}, ${k}) is not finite (${y})`);
      out[k * sampleCount + i] = y;
    }
  }
  return out;
}

/** Bilinear height of the triangulated surface gridMesh builds, at world (x, z): what a body resting there touches. */
export function meshHeightAt(heightAt: HeightFn, xMetres: number, zMetres: number, cellSizeMetres: number): number {
  const gi = Math.floor(xMetres / cellSizeMetres);
  const gk = Math.floor(zMetres / cellSizeMetres);
  const fx = xMetres / cellSizeMetres - gi;
  const fz = zMetres / cellSizeMetres - gk;
  const h00 = heightAt(gi * cellSizeMetres, gk * cellSizeMetres);
  const h10 = heightAt((gi + 1) * cellSizeMetres, gk * cellSizeMetres);
  const h01 = heightAt(gi * cellSizeMetres, (gk + 1) * cellSizeMetres);
  const h11 = heightAt((gi + 1) * cellSizeMetres, (gk + 1) * cellSizeMetres);
  // The cell's diagonal runs from (i + 1, k) to (i, k + 1): triangle (a, c, b) below it, (b, c, d) above.
  if (fx + fz <= 1) return h00 + (h10 - h00) * fx + (h01 - h00) * fz;
  return h11 + (h01 - h11) * (1 - fx) + (h10 - h11) * (1 - fz);
}
