// Tests of the world's limits: bad limits and limits whose step could overflow Jolt's fixed temp allocator are
// refused at creation; CCD bodies and constraints stop at the step budget; a nearly spent heap refuses meshes, hulls,
// height fields, characters, constraints and whole worlds with a clear Error, and the module keeps working.
import { describe, expect, it } from 'vitest';
import { CharacterController, estimateShapeBytes, PhysicsWorld, type BodyHandle, type ShapeSpec } from '../../../shared/physics/index.ts';
import { estimateWorldHeapBytes, resolveWorldLimits } from '../../../shared/physics/world-limits.ts';
import { addGround, ballast, makeWorld, run } from '../../helpers/physics.ts';

/** A flat grid mesh of size × size quads (2·size² triangles). */
function gridMesh(size: number): ShapeSpec {
  const n = size + 1;
  const positions: number[] = [];
  const indices: number[] = [];
  for (let z = 0; z < n; z++) for (let x = 0; x < n; x++) positions.push(x * 0.5, ((x * 7 + z * 3) % 5) * 0.05, z * 0.5);
  for (let z = 0; z < size; z++) {
    for (let x = 0; x < size; x++) {
      const a = z * n + x;
      indices.push(a, a + n, a + 1, a + 1, a + n, a + n + 1);
    }
  }
  return { kind: 'mesh', positions, indices };
}

/** Everything the module must still do after a refusal: step, create, remove. */
function stillWorks(w: PhysicsWorld): void {
  const ball = w.addSphere(0.2, { x: 0, y: 3, z: -50 });
  run(w, 30);
  expect(ball.position().y).toBeLessThan(3);
  w.removeBody(ball);
}

describe('world-limits', () => {
  it('refuses bad limits with a clear Error', async () => {
    await expect(PhysicsWorld.create({ maxBodies: 0 })).rejects.toThrow(/maxBodies must be an integer in \[1, 65536\], got 0/);
    await expect(PhysicsWorld.create({ maxBodies: 1.5 })).rejects.toThrow(/maxBodies must be an integer/);
    await expect(PhysicsWorld.create({ maxBodyPairs: Number.NaN })).rejects.toThrow(/maxBodyPairs must be an integer in \[64, 65536\], got NaN/);
    await expect(PhysicsWorld.create({ maxContactConstraints: 70000 })).rejects.toThrow(/maxContactConstraints must be an integer in \[64, 20000\]/);
    await expect(PhysicsWorld.create({ minFreeHeapBytes: -1 })).rejects.toThrow(/minFreeHeapBytes must be an integer/);
  });

  it('refuses limits whose step could overflow the 10 MiB temp allocator (Jolt would abort)', async () => {
    // 65536 awake bodies with 20000 contact constraints need ~15 MiB of step memory.
    await expect(PhysicsWorld.create({ maxBodies: 65536, maxContactConstraints: 20000 })).rejects.toThrow(
      /maxContactConstraints 20000 with maxBodies 65536 needs ~1\d\.\d MiB of step memory, more than Jolt's fixed 10\.0 MiB temp allocator/,
    );
    expect(() => resolveWorldLimits({ maxBodies: 10240, maxContactConstraints: 16384 })).not.toThrow();
    expect(estimateWorldHeapBytes(resolveWorldLimits({}))).toBeGreaterThan(15_000_000);
  });

  it('stops adding linear-cast bodies at the step budget, and steps with all of them awake', async () => {
    // A world sized close to the temp allocator: little step memory is left for CCD bodies.
    const w = await makeWorld({ maxBodies: 65536, maxContactConstraints: 10900, gravity: { x: 0, y: 0, z: 0 } });
    const bullets: BodyHandle[] = [];
    let refusal: Error | undefined;
    for (let i = 0; i < 5000 && !refusal; i++) {
      try {
        bullets.push(w.addSphere(0.05, { x: (i % 50) * 0.3, y: Math.floor(i / 50) * 0.3, z: 0 }, { motionQuality: 'linearCast', linearVelocity: { x: 0, y: 0, z: 50 }, allowSleeping: false }));
      } catch (err) {
        refusal = err as Error;
      }
    }
    expect(refusal?.message).toMatch(/sphere: the world's step memory is spent \(\d+ linear-cast bodies, 0 constraints; Jolt's temp allocator is a fixed 10\.0 MiB\)/);
    expect(bullets.length).toBeGreaterThan(500);
    expect(w.stepBudgetRoom('ccdBody')).toBe(0);
    const count = w.bodyCount;
    expect(w.addSphere(0.05, { x: 0, y: -5, z: 0 }).motion).toBe('dynamic'); // discrete bodies still fit
    run(w, 3); // every CCD body awake and moving: the step fits
    w.removeBody(bullets.pop()!);
    expect(w.stepBudgetRoom('ccdBody')).toBe(1);
    expect(() => w.addSphere(0.05, { x: 0, y: -9, z: 0 }, { motionQuality: 'linearCast' })).not.toThrow(); // its budget came back
    expect(w.bodyCount).toBe(count + 1);
    w.destroy();
  });

  it('stops adding constraints at the step budget and gives the budget back on removal', async () => {
    const w = await makeWorld({ maxBodies: 65536, maxContactConstraints: 11100 });
    const a = w.addBox({ x: 0.1, y: 0.1, z: 0.1 }, { x: 0, y: 0, z: 0 }, null, { motion: 'static' });
    const b = w.addBox({ x: 0.1, y: 0.1, z: 0.1 }, { x: 1, y: 0, z: 0 });
    const made = [];
    let refusal: Error | undefined;
    for (let i = 0; i < 20000 && !refusal; i++) {
      try {
        made.push(w.pointLink(a, b, { x: 0.5, y: 0, z: 0 }));
      } catch (err) {
        refusal = err as Error;
      }
    }
    expect(refusal?.message).toMatch(/addConstraint: the world's step memory is spent \(0 linear-cast bodies, \d+ constraints/);
    expect(made.length).toBeGreaterThan(500);
    run(w, 2);
    w.removeConstraint(made.pop()!);
    expect(() => w.pointLink(a, b, { x: 0.5, y: 0, z: 0 })).not.toThrow();
    w.removeBody(b); // takes every constraint with it, returning their budget
    expect(w.constraintCount).toBe(0);
    const c = w.addBox({ x: 0.1, y: 0.1, z: 0.1 }, { x: 1, y: 0, z: 0 });
    for (let i = 0; i < made.length; i++) w.pointLink(a, c, { x: 0.5, y: 0, z: 0 });
    w.destroy();
  });

  it('refuses builds that would not fit a nearly spent heap, at the estimate\'s edge, and keeps working', async () => {
    // No reserve: each build is let through right up to its estimate, so an estimate below the real peak would
    // abort the module here instead of throwing.
    const w = await makeWorld({ minFreeHeapBytes: 0 });
    addGround(w);
    const builds: Array<[string, ShapeSpec]> = [
      ['mesh', gridMesh(120)], // 28,800 triangles
      ['heightField', { kind: 'heightField', heights: Array.from({ length: 257 * 257 }, (_, i) => (i % 13) * 0.3), sampleCount: 257, cellSize: 0.5 }],
      ['convexHull', { kind: 'convexHull', points: Array.from({ length: 6000 }, (_, i) => ((i * 7919) % 1000) / 1000) }],
      ['compound', { kind: 'compound', parts: Array.from({ length: 40 }, (_, i) => ({ shape: { kind: 'convexHull' as const, points: Array.from({ length: 300 }, (_, k) => ((k * 104729 + i) % 997) / 997) }, position: { x: i, y: 0, z: 0 } })) }],
    ];
    for (const [kind, spec] of builds) {
      // Leave just over one build's estimate free: the first build is let through at the very edge of its estimate.
      const release = ballast(w, estimateShapeBytes(spec) + 64 * 1024);
      const kept: BodyHandle[] = [];
      let refusal: Error | undefined;
      try {
        for (let i = 0; i < 100 && !refusal; i++) {
          try {
            kept.push(w.addShape(spec, { x: 0, y: -20 - i, z: 0 }, null, { motion: kind === 'compound' ? 'dynamic' : 'static', gravityFactor: 0 }));
          } catch (err) {
            refusal = err as Error;
          }
        }
        expect(kept.length, kind).toBeGreaterThan(0);
        expect(refusal?.message, kind).toMatch(new RegExp(`^${kind}: the WASM heap is nearly full \\(\\d+\\.\\d MiB free, ~\\d+\\.\\d MiB needed, 0\\.0 MiB kept in reserve`));
        stillWorks(w);
      } finally {
        for (const b of kept) w.removeBody(b);
        release();
      }
    }
    const other = await makeWorld();
    other.destroy();
    w.destroy();
  });

  it('keeps its reserve: a character or constraint that would eat into it is refused', async () => {
    const w = await makeWorld({ minFreeHeapBytes: 4 * 1024 * 1024 });
    const a = w.addSphere(0.2, { x: 0, y: 0, z: 0 });
    const b = w.addSphere(0.2, { x: 1, y: 0, z: 0 });
    const release = ballast(w, 4 * 1024 * 1024 + 1024); // less than any of the three needs on top of the reserve
    try {
      expect(() => new CharacterController(w, { position: { x: 0, y: 0, z: 0 } })).toThrow(/CharacterController: the WASM heap is nearly full/);
      expect(() => w.pointLink(a, b, { x: 0.5, y: 0, z: 0 })).toThrow(/addConstraint: the WASM heap is nearly full/);
      expect(() => w.addBox({ x: 1, y: 1, z: 1 }, { x: 0, y: 0, z: 0 })).toThrow(/box: the WASM heap is nearly full/);
      expect(w.bodyCount).toBe(2);
      expect(w.constraintCount).toBe(0);
      run(w, 10); // stepping needs no new heap
    } finally {
      release();
    }
    new CharacterController(w, { position: { x: 3, y: 0, z: 0 } }).destroy();
    w.destroy();
  });

  it('refuses a world the heap cannot hold, and the worlds already made keep working', async () => {
    const worlds: PhysicsWorld[] = [];
    let refusal: Error | undefined;
    for (let i = 0; i < 12 && !refusal; i++) {
      try {
        worlds.push(await makeWorld());
      } catch (err) {
        refusal = err as Error;
      }
    }
    expect(refusal?.message).toMatch(/PhysicsWorld\.create: the WASM heap has \d+\.\d MiB free, a world with these limits needs ~1\d\.\d MiB/);
    expect(worlds.length).toBeGreaterThanOrEqual(5); // ~15 MB each of the 128 MB heap
    for (const w of worlds) {
      const ball = w.addSphere(0.2, { x: 0, y: 1, z: 0 });
      run(w, 5);
      expect(ball.position().y).toBeLessThan(1);
    }
    for (const w of worlds) w.destroy();
    const again = await makeWorld();
    again.destroy();
  });
});
