// The `taos-physics/physics` entry in browsers: the Jolt wrapper (worlds, bodies, shapes, characters, constraints,
// queries). Load Jolt with loadJolt({ wasmUrl }). Node resolves the entry to physics-node.ts instead.
export * from '../shared/physics/index.ts';
