// Tests of the Jolt loader: a clear Error when no .wasm was given, then one memoized module for every caller.
// This file deliberately does not import server/physics-node.ts, so no default .wasm is registered.
import { readFileSync } from 'node:fs';
import { createRequire } from 'node:module';
import { describe, expect, it } from 'vitest';
import { createJoltInstance, getJolt, initializePhysics, isPhysicsInitialized, loadJolt, PhysicsWorld } from '../../../shared/physics/index.ts';

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

  it('creates independent module instances with their own heaps that simulate identically', async () => {
    const wasmBinary = readFileSync(wasmPath);
    const shared = await loadJolt({ wasmBinary });
    const a = await createJoltInstance({ wasmBinary });
    const b = await createJoltInstance({ wasmBinary });
    expect(a).not.toBe(shared);
    expect(a).not.toBe(b);
    expect(a.HEAPU8.buffer).not.toBe(b.HEAPU8.buffer);
    const drop = async (opts: Parameters<typeof PhysicsWorld.create>[0]): Promise<Float32Array> => {
      const world = await PhysicsWorld.create(opts);
      world.addBox({ x: 10, y: 0.5, z: 10 }, { x: 0, y: -0.5, z: 0 }, null, { motion: 'static' });
      for (let i = 0; i < 20; i++) world.addBox({ x: 0.3, y: 0.3, z: 0.3 }, { x: (i % 4) * 0.4, y: 1 + i * 0.7, z: 0 });
      for (let t = 0; t < 120; t++) world.stepFixed();
      const states = world.readBodyStates().states.slice();
      world.destroy();
      return states;
    };
    const onShared = await drop({ wasmBinary });
    const onA = await drop({ jolt: a });
    const isolated = await drop({ wasmBinary, isolatedModule: true });
    expect(new Uint32Array(onA.buffer)).toEqual(new Uint32Array(onShared.buffer));
    expect(new Uint32Array(isolated.buffer)).toEqual(new Uint32Array(onShared.buffer));
    const freeA = a.JoltInterface.prototype.sGetFreeMemory();
    const world = await PhysicsWorld.create({ jolt: b });
    expect(a.JoltInterface.prototype.sGetFreeMemory()).toBe(freeA); // a world on b takes nothing from a's heap
    world.destroy();
  });
});
