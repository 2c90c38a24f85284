// The `taos-physics/physics` entry in Node: the Jolt wrapper, with the package's own .wasm registered as the default
// (so PhysicsWorld.create() needs no options) and loadJoltNode() / joltWasmPath().
export * from './physics.ts';
export { joltWasmPath, loadJoltNode } from '../server/physics-node.ts';
