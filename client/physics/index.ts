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

/**
 * Downloads and compiles Jolt (once per page); every Simulation.create after it loads nothing more. The page fetches
 * the .wasm itself, so a failed download is a rejected promise with a clear message, not the engine's console noise.
 */
export async function startPhysics(): Promise<void> {
  const url = joltWasmUrl();
  let res: Response;
  try {
    res = await fetch(url);
  } catch (err) {
    throw new Error(`the physics engine could not be downloaded from ${url}: ${(err as Error).message}`, { cause: err });
  }
  if (!res.ok) throw new Error(`the physics engine could not be downloaded from ${url}: HTTP ${res.status}`);
  // Jolt's browser glue loads only from a URL (it ignores wasmBinary): hand it the downloaded bytes as one, kept for
  // the page's lifetime (every room's world instantiates from it).
  const bytes = await res.arrayBuffer();
  setDefaultPhysicsInitOptions({ wasmUrl: URL.createObjectURL(new Blob([bytes], { type: 'application/wasm' })) });
  await initializePhysics();
}

