// Test helpers for the physics layer: a world loaded with the package's .wasm, a ground slab, stepping until bodies
// sleep, small vector utilities and raw heap ballast for nearly-full-heap tests.
import '../../server/physics-node.ts';
import { PhysicsWorld, type BodyHandle, type BodyOptions, type PhysicsWorldOptions, type QuatLike, type Vec3Like } from '../../shared/physics/index.ts';

/** A fresh world (Jolt loaded from node_modules). */
export function makeWorld(opts: PhysicsWorldOptions = {}): Promise<PhysicsWorld> {
  return PhysicsWorld.create(opts);
}

/** Steps the world `ticks` fixed ticks. */
export function run(world: PhysicsWorld, ticks: number): void {
  for (let i = 0; i < ticks; i++) world.stepFixed();
}

/** Free bytes in the WASM heap. */
export function freeBytes(world: PhysicsWorld): number {
  return world.freeHeapBytes();
}

/** A static 100 m × 100 m ground slab whose top face is y = 0. */
export function addGround(world: PhysicsWorld, opts: BodyOptions = {}): BodyHandle {
  return world.addBox({ x: 50, y: 0.5, z: 50 }, { x: 0, y: -0.5, z: 0 }, null, { motion: 'static', ...opts });
}

/** Steps until every given body sleeps (or `maxTicks` pass); returns the ticks stepped. */
export function settle(world: PhysicsWorld, bodies: BodyHandle[], maxTicks = 600): number {
  for (let t = 1; t <= maxTicks; t++) {
    world.stepFixed();
    if (bodies.every((b) => !b.isActive())) return t;
  }
  return maxTicks;
}

/** Euclidean distance between two points. */
export function distance(a: Vec3Like, b: Vec3Like): number {
  const dx = a.x - b.x;
  const dy = a.y - b.y;
  const dz = a.z - b.z;
  return Math.sqrt(dx * dx + dy * dy + dz * dz);
}

/** Rotates v by the unit quaternion q. */
export function rotate(q: QuatLike, v: Vec3Like): Vec3Like {
  const tx = 2 * (q.y * v.z - q.z * v.y);
  const ty = 2 * (q.z * v.x - q.x * v.z);
  const tz = 2 * (q.x * v.y - q.y * v.x);
  return {
    x: v.x + q.w * tx + (q.y * tz - q.z * ty),
    y: v.y + q.w * ty + (q.z * tx - q.x * tz),
    z: v.z + q.w * tz + (q.x * ty - q.y * tx),
  };
}

/** Raw WASM allocations that eat heap without Jolt knowing: brings free memory down to about `targetFreeBytes`. */
export function ballast(w: PhysicsWorld, targetFreeBytes: number): () => void {
  const J = w.jolt as unknown as { _webidl_malloc(n: number): number; _webidl_free(p: number): void };
  const blocks: number[] = [];
  let chunk = 4 * 1024 * 1024;
  while (w.freeHeapBytes() > targetFreeBytes + 256) {
    const room = w.freeHeapBytes() - targetFreeBytes;
    while (chunk > 128 && chunk > room) chunk >>= 1;
    const p = J._webidl_malloc(chunk);
    if (p === 0) break;
    blocks.push(p);
  }
  return () => {
    for (const p of blocks.reverse()) J._webidl_free(p);
  };
}
