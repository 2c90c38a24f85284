// Test helpers for the physics layer: a world loaded with the package's .wasm, and step/free-memory utilities.
import '../../server/physics-node.ts';
import { PhysicsWorld, type PhysicsWorldOptions } from '../../shared/physics/index.ts';

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
