// The physics chunk: the browser's own Simulation (Jolt included), which a page loads with a dynamic import() only
// when it needs it. The build emits this chunk and Jolt's .wasm as separate, content-hashed files under chunks/.
import { initializePhysics, setDefaultPhysicsInitOptions } from '../../shared/physics/index.ts';

export { getScenario, listScenarios } from '../../scenarios/index.ts';
export { Simulation } from '../../shared/sim/simulation.ts';
export { ReplayPlayer, type ReplayVerification } from './replay-player.ts';

/** The .wasm's file name beside this chunk; scripts/build-client.ts defines it (content-hashed). */
declare const __TAOS_JOLT_WASM_FILE__: string;
/** The name used when this module runs unbundled. */
const UNBUNDLED_WASM_FILE = 'jolt-physics.wasm';

/** The URL of Jolt's .wasm, next to this chunk. */
export function joltWasmUrl(): string {
  const file = typeof __TAOS_JOLT_WASM_FILE__ === 'string' ? __TAOS_JOLT_WASM_FILE__ : UNBUNDLED_WASM_FILE;
  return new URL(file, import.meta.url).href;
}

/** Fetches and compiles Jolt (once per page); every Simulation.create after it loads nothing more. */
export async function startPhysics(): Promise<void> {
  setDefaultPhysicsInitOptions({ wasmUrl: joltWasmUrl() });
  await initializePhysics();
}

