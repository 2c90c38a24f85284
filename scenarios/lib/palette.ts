// Render colours shared by the scenarios: one named, linear-RGB colour per kind of thing, so scenes read alike.
// Plain data only; clients draw bodies with the colour their BodyDescriptor carries.
import type { Rgb } from '../../shared/sim/scenario.ts';

/** Named colours, components in [0, 1]. */
export const Palette = {
  ground: [0.36, 0.42, 0.33],
  wall: [0.62, 0.6, 0.56],
  stone: [0.5, 0.5, 0.52],
  terrain: [0.42, 0.5, 0.3],
  snow: [0.72, 0.77, 0.84],
  wood: [0.55, 0.38, 0.22],
  metal: [0.55, 0.58, 0.62],
  door: [0.72, 0.32, 0.18],
  platform: [0.25, 0.45, 0.75],
  trigger: [0.95, 0.85, 0.2],
  target: [0.86, 0.16, 0.16],
  anchor: [0.2, 0.2, 0.22],
  player: [0.95, 0.55, 0.1],
} as const satisfies Record<string, Rgb>;

/** Bright colours for dynamic props, picked by the scenario's PRNG. */
export const PROP_COLORS: readonly Rgb[] = [
  [0.9, 0.3, 0.25],
  [0.95, 0.6, 0.2],
  [0.95, 0.85, 0.3],
  [0.45, 0.8, 0.35],
  [0.25, 0.7, 0.75],
  [0.3, 0.45, 0.9],
  [0.6, 0.35, 0.85],
  [0.9, 0.4, 0.65],
];
