// Bullets: where a shot starts (the shooter's eye, pushed along the aim until it is clear of the shooter's capsule),
// the body it becomes (a small CCD sphere on the Bullet layer) and the live list with each bullet's expiry tick.
import { CollisionLayer, type ShapeSpec, type Vec3Like } from '../physics/index.ts';
import { CHARACTER_HALF_HEIGHT_METRES, CHARACTER_RADIUS_METRES, EYE_HEIGHT_METRES } from './players.ts';
import type { SpawnOptions } from './scenario.ts';

/** Bullet sphere radius (m) and mass (kg). */
export const BULLET_RADIUS_METRES = 0.05;
export const BULLET_MASS_KG = 0.2;
/** Extra gap (m) between the shooter's capsule and a new bullet's surface. */
const MUZZLE_GAP_METRES = 0.1;

/** The shape every bullet has. */
export const BULLET_SHAPE: ShapeSpec = Object.freeze({ kind: 'sphere', radius: BULLET_RADIUS_METRES }) as ShapeSpec;

/** One live bullet. */
export interface Bullet {
  bodyId: number;
  ownerId: number;
  /** The tick at whose end the bullet is removed. */
  expireTick: number;
}

/**
 * Distance along unit `aim` from the eye (on the capsule's axis) to where the ray leaves the shooter's capsule
 * (feet at y = 0, axis from y = r to y = r + 2h, radius r).
 */
export function capsuleExitDistance(aim: Vec3Like, eyeHeight = EYE_HEIGHT_METRES, radius = CHARACTER_RADIUS_METRES, halfHeight = CHARACTER_HALF_HEIGHT_METRES): number {
  const bottom = radius;
  const top = radius + 2 * halfHeight;
  const horizontal = Math.sqrt(aim.x * aim.x + aim.z * aim.z);
  // Height where the ray reaches the cylinder's radius (±∞ when it goes straight up or down).
  const y = horizontal > 1e-9 ? eyeHeight + (radius / horizontal) * aim.y : aim.y >= 0 ? Infinity : -Infinity;
  if (y >= bottom && y <= top) return radius / horizontal;
  // Leaves through the hemispherical cap on that side: solve |e + t·aim - c| = r with e - c = (0, d, 0).
  const d = eyeHeight - (y > top ? top : bottom);
  const b = d * aim.y;
  return -b + Math.sqrt(b * b - d * d + radius * radius);
}

/** Where a bullet fired by a character standing at `feet` along unit `aim` starts: clear of the shooter. */
export function muzzlePosition(feet: Vec3Like, aim: Vec3Like): Vec3Like {
  const t = capsuleExitDistance(aim) + BULLET_RADIUS_METRES + MUZZLE_GAP_METRES;
  return { x: feet.x + aim.x * t, y: feet.y + EYE_HEIGHT_METRES + aim.y * t, z: feet.z + aim.z * t };
}

/** Body options of a bullet fired by the player whose no-collide group is `shooterGroup`. */
export function bulletOptions(aim: Vec3Like, speedMetresPerSecond: number, hitsPlayers: boolean, shooterGroup: number, shooterId: number): SpawnOptions {
  const mask = CollisionLayer.World | CollisionLayer.Enemy | CollisionLayer.Prop | (hitsPlayers ? CollisionLayer.Player : 0);
  return {
    motion: 'dynamic',
    layer: CollisionLayer.Bullet,
    mask,
    motionQuality: 'linearCast',
    massKg: BULLET_MASS_KG,
    restitution: 0.3,
    friction: 0.4,
    linearVelocity: { x: aim.x * speedMetresPerSecond, y: aim.y * speedMetresPerSecond, z: aim.z * speedMetresPerSecond },
    noCollideGroup: shooterGroup,
    name: `bullet of player ${shooterId}`,
  };
}

/** Live bullets in firing order (which is ascending body id). */
export class BulletList {
  private bullets: Bullet[] = [];

  add(b: Bullet): void {
    this.bullets.push(b);
  }

  /** Takes the bullets whose lifetime ends at `tick` (their bodies are the caller's to remove). */
  takeExpired(tick: number): Bullet[] {
    if (this.bullets.length === 0 || this.bullets[0].expireTick > tick) return [];
    const out: Bullet[] = [];
    const keep: Bullet[] = [];
    for (const b of this.bullets) (b.expireTick <= tick ? out : keep).push(b);
    this.bullets = keep;
    return out;
  }

  /** Forgets a bullet whose body was removed for another reason (left the bounds). */
  forget(bodyId: number): void {
    const i = this.bullets.findIndex((b) => b.bodyId === bodyId);
    if (i >= 0) this.bullets.splice(i, 1);
  }

  has(bodyId: number): boolean {
    return this.bullets.some((b) => b.bodyId === bodyId);
  }

  /** The live bullets themselves, in list order (read-only: for hashing without copies). */
  live(): readonly Readonly<Bullet>[] {
    return this.bullets;
  }

  /** Copies of the live bullets. */
  snapshot(): Bullet[] {
    return this.bullets.map((b) => ({ ...b }));
  }

  /** Replaces the list (checkpoint restore). */
  restore(bullets: readonly Bullet[]): void {
    this.bullets = bullets.map((b) => ({ ...b }));
  }

  get size(): number {
    return this.bullets.length;
  }
}
