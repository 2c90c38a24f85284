// Tests of the Jolt loader: a clear Error when no .wasm was given, then one memoized module for every caller.
// This file deliberately does not import server/physics-node.ts, so no default .wasm is registered.
import { readFileSync } from 'node:fs';
import { createRequire } from 'node:module';
import { describe, expect, it } from 'vitest';
import { getJolt, initializePhysics, isPhysicsInitialized, loadJolt, PhysicsWorld } from '../../../shared/physics/index.ts';

const wasmPath = createRequire(import.meta.url).resolve('jolt-physics/jolt-physics.wasm.wasm');

describe('jolt-backend', () => {
  it('tells the caller how to load Jolt when no .wasm was given, and can be retried', async () => {
    expect(isPhysicsInitialized()).toBe(false);
    expect(() => getJolt()).toThrow(/Jolt is not loaded yet: await initializePhysics\(\)/);
    await expect(loadJolt()).rejects.toThrow(/no wasmBinary or wasmUrl given. In Node import server\/physics-node.ts/);
    await expect(PhysicsWorld.create()).rejects.toThrow(/no wasmBinary or wasmUrl given/);
    expect(isPhysicsInitialized()).toBe(false);
  });

  it('loads once from the given bytes and hands every later caller the same module', async () => {
    const wasmBinary = readFileSync(wasmPath);
    const J = await loadJolt({ wasmBinary });
    expect(isPhysicsInitialized()).toBe(true);
    expect(getJolt()).toBe(J);
    expect(await loadJolt()).toBe(J); // no options needed any more
    expect(await loadJolt({ wasmUrl: 'ignored-once-loaded.wasm' })).toBe(J);
    await initializePhysics();
    expect(J.HEAP8.length).toBe(128 * 1024 * 1024); // the fixed heap
    const w = await PhysicsWorld.create();
    expect(w.jolt).toBe(J);
    w.destroy();
  });
});
