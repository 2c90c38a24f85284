// pendulum-chain: rows of sphere chains hanging from static anchors by point (ball-and-socket) links, released
// from a tilt so they swing and whip through rows of standing pins on the ground below.
import { pointLink } from '../shared/physics/index.ts';
import { detCos, detSin } from '../shared/sim/det-math.ts';
import type { ScenarioContext, ScenarioDefinition, ScenarioInstance } from '../shared/sim/scenario.ts';
import { Palette, PROP_COLORS } from './lib/palette.ts';
import { addGround } from './lib/static-scene.ts';

const DEG = Math.PI / 180;
const PIN_HALF = { x: 0.1, y: 0.4, z: 0.1 };
const LINK_VELOCITY_STEPS = 20;
const LINK_POSITION_STEPS = 6;

/** Point-linked sphere chains swinging into pins. */
export const scenario: ScenarioDefinition = {
  name: 'pendulum-chain',
  description: 'Chains of spheres hang from anchors by point links, swing from a tilt and knock over rows of pins.',
  params: {
    chains: { default: 5, min: 1, max: 40, integer: true, description: 'number of chains, side by side' },
    links: { default: 12, min: 1, max: 60, integer: true, description: 'spheres per chain' },
    linkLengthMetres: { default: 0.5, min: 0.2, max: 2, description: 'distance between consecutive sphere centres (m)' },
    sphereRadiusMetres: { default: 0.18, min: 0.05, max: 0.5, description: 'sphere radius (m); must be under half the link length' },
    startAngleDegrees: { default: 70, min: 0, max: 170, description: 'tilt of each chain from the vertical at the start (°, ±10° seeded jitter)' },
    pinsPerChain: { default: 5, min: 0, max: 20, integer: true, description: 'pins standing in each chain’s swing path' },
  },
  bounds: { min: { x: -60, y: -10, z: -150 }, max: { x: 60, y: 140, z: 150 } },
  golden: { ticks: 300, bots: 1 },
  build(ctx: ScenarioContext): ScenarioInstance {
    const p = ctx.params;
    const L = p.linkLengthMetres;
    const r = p.sphereRadiusMetres;
    if (2 * r >= L) throw new Error(`scenario pendulum-chain: sphereRadiusMetres (${r}) must be under half of linkLengthMetres (${L}) so linked spheres do not overlap`);
    const length = p.links * L;
    const anchorY = length + r + 0.5;
    const spacing = Math.max(1.2, 4 * r + 0.6);
    const rowHalf = ((p.chains - 1) * spacing) / 2;
    addGround(ctx, Math.max(rowHalf + 6, length + 6));
    for (let c = 0; c < p.chains; c++) {
      const x = -rowHalf + c * spacing;
      const anchor = ctx.spawn({ kind: 'sphere', radius: r * 0.8 }, { x, y: anchorY, z: 0 }, null, { motion: 'static', color: Palette.anchor, name: `anchor ${c}` });
      const angle = (p.startAngleDegrees + ctx.rng.range(-10, 10)) * DEG;
      const side = c % 2 === 0 ? -1 : 1; // neighbours start on opposite sides, so the row swings in counterpoint
      const dir = { y: -detCos(angle), z: side * detSin(angle) };
      const color = PROP_COLORS[c % PROP_COLORS.length];
      let prev = anchor;
      const starts: Array<{ y: number; z: number }> = [];
      for (let k = 1; k <= p.links; k++) {
        const pos = { x, y: anchorY + dir.y * k * L, z: dir.z * k * L };
        starts.push(pos);
        const sphere = ctx.spawn({ kind: 'sphere', radius: r }, pos, null, { motion: 'dynamic', friction: 0.3, restitution: 0.1, color, name: `chain ${c} link ${k}` });
        // The pivot is the upper body's centre, so the centre-to-centre distance of each pair stays L.
        const link = pointLink(ctx.world, prev, sphere, prev.position());
        // Extra solver iterations for the links: a long chain otherwise stretches visibly when it whips.
        link.SetNumVelocityStepsOverride(LINK_VELOCITY_STEPS);
        link.SetNumPositionStepsOverride(LINK_POSITION_STEPS);
        prev = sphere;
      }
      // Pins stand along the swing path wherever the lowest sphere passes below their tops.
      const drop = anchorY - r - 2 * PIN_HALF.y;
      const reach = Math.sqrt(Math.max(0, length * length - drop * drop));
      for (let i = 0; i < p.pinsPerChain; i++) {
        const z = p.pinsPerChain === 1 ? 0 : -reach + (2 * reach * i) / (p.pinsPerChain - 1);
        // A chain released nearly upright would start inside a pin: leave that pin out.
        if (starts.some((s) => Math.abs(s.z - z) < r + PIN_HALF.z + 0.05 && s.y - r < 2 * PIN_HALF.y + 0.05)) continue;
        ctx.spawn({ kind: 'box', halfExtents: PIN_HALF }, { x, y: PIN_HALF.y, z }, null, { motion: 'dynamic', friction: 0.5, color: Palette.wood, name: `pin ${c}.${i}` });
      }
    }
    return {
      spawnPoint(playerIndex: number) {
        const slot = playerIndex % 8;
        return { x: -rowHalf - 2 + slot * 0.9, y: 0.05, z: length + 3 };
      },
    };
  },
};
