// Tests for scenarios/lib/terrain-heights.ts: the bowl rises to its rim, the mountain peaks at the origin and falls
// away with distance, and both depend on the seed only through their noise.
import { describe, expect, it } from 'vitest';
import { bowlTerrain, mountainTerrain } from '../../../scenarios/lib/terrain-heights.ts';

describe('terrain-heights', () => {
  it('raises the bowl by rimMetres from its centre to radiusMetres', () => {
    const flat = bowlTerrain(1, { amplitudeMetres: 0, featureMetres: 5, rimMetres: 4, radiusMetres: 20 });
    expect(flat(0, 0)).toBe(0);
    expect(flat(20, 0)).toBeCloseTo(4, 12);
    expect(flat(0, -10)).toBeCloseTo(1, 12);
    const hilly = bowlTerrain(1, { amplitudeMetres: 3, featureMetres: 5, rimMetres: 4, radiusMetres: 20 });
    for (let x = -20; x <= 20; x += 2.5) expect(Math.abs(hilly(x, 3) - flat(x, 3))).toBeLessThanOrEqual(1.5);
  });

  it('peaks at the origin and halves at mountainWidth, within its roughness', () => {
    const opts = { peakMetres: 40, halfWidthMetres: 30, roughnessMetres: 2, featureMetres: 10 };
    const h = mountainTerrain(9, opts);
    expect(Math.abs(h(0, 0) - 40)).toBeLessThanOrEqual(1);
    expect(Math.abs(h(30, 0) - 20)).toBeLessThanOrEqual(1);
    expect(Math.abs(h(0, -90) - 4)).toBeLessThanOrEqual(1);
    expect(mountainTerrain(9, opts)(12.3, 4.5)).toBe(h(12.3, 4.5));
    expect(mountainTerrain(10, opts)(12.3, 4.5)).not.toBe(h(12.3, 4.5));
  });
});
