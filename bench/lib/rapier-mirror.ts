// A Rapier copy of a Jolt scene for the engine-peer figure: every body of a Simulation (shape, pose, velocities,
// mass, friction, restitution, damping, read from the Jolt body itself) rebuilt in @dimforge/rapier3d-deterministic-compat.
import RAPIER from '@dimforge/rapier3d-deterministic-compat';
import { BODY_STATE_STRIDE, BodyFlag, type ShapeSpec } from '../../shared/physics/index.ts';
import type { Simulation } from '../../shared/sim/simulation.ts';
import { TICK_DT_SECONDS } from '../../shared/tick-rate.ts';

let initialized: Promise<void> | null = null;

/** Loads Rapier's WASM once per process. */
export function initRapier(): Promise<void> {
  initialized ??= RAPIER.init();
  return initialized;
}

/** A Rapier world built from a simulation, with what was copied. */
export interface RapierMirror {
  world: RAPIER.World;
  bodies: number;
  /** Shape kinds that had no Rapier counterpart (skipped). */
  skipped: string[];
  /** Frees the Rapier world. */
  free(): void;
}

function colliderFor(shape: ShapeSpec): RAPIER.ColliderDesc | null {
  switch (shape.kind) {
    case 'box':
      return RAPIER.ColliderDesc.cuboid(shape.halfExtents.x, shape.halfExtents.y, shape.halfExtents.z);
    case 'sphere':
      return RAPIER.ColliderDesc.ball(shape.radius);
    case 'capsule':
      return RAPIER.ColliderDesc.capsule(shape.halfHeight, shape.radius);
    case 'cylinder':
      return RAPIER.ColliderDesc.cylinder(shape.halfHeight, shape.radius);
    case 'convexHull':
      return RAPIER.ColliderDesc.convexHull(Float32Array.from(shape.points));
    default:
      return null;
  }
}

/** Rebuilds every body of `sim` (in id order) in a new Rapier world with the same gravity and a 1/60 s step. */
export async function mirrorInRapier(sim: Simulation): Promise<RapierMirror> {
  await initRapier();
  const world = new RAPIER.World({ x: 0, y: -9.81, z: 0 }); // owned by the mirror; free() releases it
  world.timestep = TICK_DT_SECONDS;
  const read = sim.readBodyStates();
  const skipped: string[] = [];
  let bodies = 0;
  for (let i = 0; i < read.count; i++) {
    const id = read.ids[i];
    const handle = sim.world.getBody(id);
    const shape = handle?.shape;
    if (!handle || !shape) continue;
    const collider = colliderFor(shape);
    if (!collider) {
      skipped.push(shape.kind);
      continue;
    }
    const s = read.states.subarray(i * BODY_STATE_STRIDE, (i + 1) * BODY_STATE_STRIDE);
    const isStatic = (read.flags[i] & BodyFlag.Static) !== 0;
    const raw = handle.raw;
    const desc = (isStatic ? RAPIER.RigidBodyDesc.fixed() : RAPIER.RigidBodyDesc.dynamic())
      .setTranslation(s[0], s[1], s[2])
      .setRotation({ x: s[3], y: s[4], z: s[5], w: s[6] });
    if (!isStatic) {
      const mp = raw.GetMotionProperties();
      desc.setLinvel(s[7], s[8], s[9]).setAngvel({ x: s[10], y: s[11], z: s[12] });
      desc.setLinearDamping(mp.GetLinearDamping()).setAngularDamping(mp.GetAngularDamping());
      const inverseMass = mp.GetInverseMassUnchecked();
      if (inverseMass > 0) collider.setMass(1 / inverseMass);
    }
    // Jolt combines friction as the geometric mean and restitution as the maximum: with Rapier's Multiply rule,
    // √f per collider gives √(f1·f2).
    collider.setFriction(Math.sqrt(raw.GetFriction())).setRestitution(raw.GetRestitution());
    collider.setFrictionCombineRule(RAPIER.CoefficientCombineRule.Multiply);
    collider.setRestitutionCombineRule(RAPIER.CoefficientCombineRule.Max);
    const body = world.createRigidBody(desc);
    world.createCollider(collider, body);
    bodies++;
  }
  return { world, bodies, skipped, free: () => world.free() };
}
