// Node-only helper: finds jolt-physics' .wasm in node_modules and registers its bytes as the default for loadJolt.
// Import it (for its side effect or loadJoltNode) before creating a PhysicsWorld in Node.
import { readFileSync } from 'node:fs';
import { createRequire } from 'node:module';
import { loadJolt, setDefaultPhysicsInitOptions, type JoltModule } from '../shared/physics/index.ts';

const require = createRequire(import.meta.url);

/** Absolute path of the single-threaded jolt-physics .wasm file. */
export function joltWasmPath(): string {
  return require.resolve('jolt-physics/jolt-physics.wasm.wasm');
}

let registered = false;

/** Registers the package's .wasm bytes as loadJolt's default (idempotent). */
export function registerNodeJolt(): void {
  if (registered) return;
  registered = true;
  setDefaultPhysicsInitOptions({ wasmBinary: readFileSync(joltWasmPath()) });
}

/** Loads Jolt in Node with the package's own .wasm. */
export async function loadJoltNode(): Promise<JoltModule> {
  registerNodeJolt();
  return loadJolt();
}

registerNodeJolt();
