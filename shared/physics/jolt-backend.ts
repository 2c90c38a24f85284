// Loads the single-threaded Jolt WASM module once (memoized) and hands out the module object.
// This and the other files of shared/physics are the only code that names jolt-physics; it stays isomorphic.
import type JoltFactory from 'jolt-physics/wasm';

/** The loaded Jolt module: every Jolt class and enum hangs off it. */
export type JoltModule = Awaited<ReturnType<typeof JoltFactory>>;

/** How to find the `.wasm`: hand over its bytes (Node) or its URL (browser). */
export interface PhysicsInitOptions {
  /** The bytes of `jolt-physics/dist/jolt-physics.wasm.wasm`. */
  wasmBinary?: ArrayBuffer | Uint8Array;
  /** A URL the browser can fetch the `.wasm` from. */
  wasmUrl?: string;
}

let loadPromise: Promise<JoltModule> | null = null;
let loaded: JoltModule | null = null;
let defaultOptions: PhysicsInitOptions | null = null;

/**
 * Registers how to load the module when a caller passes no options (the Node helper in server/ does this,
 * so shared code never reads files). Has no effect once the module is loaded.
 */
export function setDefaultPhysicsInitOptions(opts: PhysicsInitOptions): void {
  defaultOptions = opts;
}

function chooseOptions(opts?: PhysicsInitOptions): PhysicsInitOptions {
  const chosen = opts && (opts.wasmBinary || opts.wasmUrl) ? opts : (defaultOptions ?? {});
  if (!chosen.wasmBinary && !chosen.wasmUrl) {
    throw new Error(
      'loadJolt: no wasmBinary or wasmUrl given. In Node import server/physics-node.ts (it registers the ' +
        "package's .wasm); in the browser pass { wasmUrl } pointing at jolt-physics.wasm.wasm.",
    );
  }
  return chosen;
}

async function joltFactory(): Promise<typeof JoltFactory> {
  const { default: factory } = await import('jolt-physics/wasm');
  return factory;
}

/** Loads Jolt once; later calls (with any options) return the same module. */
export function loadJolt(opts?: PhysicsInitOptions): Promise<JoltModule> {
  if (!loadPromise) {
    loadPromise = (async () => {
      const chosen = chooseOptions(opts);
      const factory = await joltFactory();
      const moduleArgs: { locateFile?: (path: string) => string; wasmBinary?: ArrayBuffer | Uint8Array } = {};
      if (chosen.wasmBinary) {
        moduleArgs.wasmBinary = chosen.wasmBinary;
      } else {
        const url = chosen.wasmUrl!;
        moduleArgs.locateFile = () => url;
      }
      const module: JoltModule = await factory(moduleArgs);
      loaded = module;
      return module;
    })();
    loadPromise.catch(() => {
      loadPromise = null; // a failed load may be retried with other options
    });
  }
  return loadPromise;
}

let compiled: { key: PhysicsInitOptions['wasmBinary'] | string; module: Promise<WebAssembly.Module> } | null = null;

function compiledWasm(chosen: PhysicsInitOptions): Promise<WebAssembly.Module> {
  const key = chosen.wasmBinary ?? chosen.wasmUrl!;
  if (!compiled || compiled.key !== key) {
    const module = chosen.wasmBinary
      ? WebAssembly.compile(chosen.wasmBinary as BufferSource)
      : fetch(chosen.wasmUrl!).then((r) => {
          if (!r.ok) throw new Error(`createJoltInstance: fetching ${chosen.wasmUrl} failed: HTTP ${r.status}`);
          return r.arrayBuffer();
        }).then((bytes) => WebAssembly.compile(bytes));
    compiled = { key, module };
    module.catch(() => {
      if (compiled?.module === module) compiled = null;
    });
  }
  return compiled.module;
}

/**
 * Instantiates a NEW, independent Jolt module with its own fixed 128 MB heap (the .wasm is compiled once per
 * process and reused). Worlds built on it share nothing with other modules: one room running out of memory or
 * aborting cannot touch another, and a world's heap history depends only on its own session (replays match).
 */
export async function createJoltInstance(opts?: PhysicsInitOptions): Promise<JoltModule> {
  const chosen = chooseOptions(opts);
  const [factory, wasm]: [typeof JoltFactory, WebAssembly.Module] = await Promise.all([joltFactory(), compiledWasm(chosen)]);
  const instantiateWasm = (imports: WebAssembly.Imports, receive: (instance: WebAssembly.Instance) => void): Record<string, never> => {
    WebAssembly.instantiate(wasm, imports).then(receive, (err: unknown) => {
      throw err;
    });
    return {};
  };
  return factory({ instantiateWasm });
}

/** Awaits the module; call once at start-up (PhysicsWorld.create does it for you). */
export async function initializePhysics(opts?: PhysicsInitOptions): Promise<void> {
  await loadJolt(opts);
}

/** Whether the module has finished loading. */
export function isPhysicsInitialized(): boolean {
  return loaded !== null;
}

/** The loaded module, or an Error telling the caller to await initializePhysics first. */
export function getJolt(): JoltModule {
  if (!loaded) throw new Error('Jolt is not loaded yet: await initializePhysics() or PhysicsWorld.create() first');
  return loaded;
}
