// The `taos-physics/physics` entry: the Jolt wrapper (worlds, bodies, shapes, characters, constraints, queries).
// In Node, loadJoltNode() loads the package's .wasm; browsers pass wasmUrl to loadJolt.
export * from '../shared/physics/index.ts';
export { joltWasmPath, loadJoltNode } from '../server/physics-node.ts';
