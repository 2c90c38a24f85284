// WASM memory tests: free heap is unchanged after 10,000 create/destroy cycles of every factory, sensor bodies,
// constraints, characters and ray casts, after clear(), and across world create/destroy cycles.
// Set PHYSICS_MEMORY_REPORT=1 to print the measured figures (docs/physics.md quotes them).
import { afterAll, describe, expect, it } from 'vitest';
import { CharacterController, distanceLink, hingeLink, sliderLink, type BodyHandle, type PhysicsWorld, type ShapeSpec } from '../../../shared/physics/index.ts';
import { addGround, makeWorld } from '../../helpers/physics.ts';

const CYCLES = 10_000;
const BATCH = 100;
const figures: string[] = [];

/**
 * Runs `round(batch)` as a warm-up (allocator caches fill), takes the baseline, runs CYCLES / BATCH more rounds and
 * returns free heap before and after. Each round creates and destroys `batch` things and steps the world once.
 */
function measure(w: PhysicsWorld, label: string, round: (batch: number) => void, batch = BATCH, cycles = CYCLES): { before: number; after: number } {
  round(batch);
  round(batch);
  w.stepFixed();
  const before = w.freeHeapBytes();
  for (let done = 0; done < cycles; done += batch) round(batch);
  w.stepFixed();
  const after = w.freeHeapBytes();
  figures.push(`${label.padEnd(14)} ${String(cycles).padStart(6)} cycles (rounds of ${batch})  free before ${before}  after ${after}  diff ${after - before}`);
  return { before, after };
}

/** A round that adds `batch` bodies of one spec, steps once so they simulate, then removes them. */
function bodyRound(w: PhysicsWorld, spec: ShapeSpec, opts: Parameters<PhysicsWorld['addShape']>[3]): (batch: number) => void {
  return (batch) => {
    const bodies: BodyHandle[] = [];
    for (let i = 0; i < batch; i++) bodies.push(w.addShape(spec, { x: (i % 10) * 1.5 - 7, y: 1 + Math.floor(i / 10) * 1.5, z: 0 }, null, opts));
    w.stepFixed();
    for (const b of bodies) w.removeBody(b);
  };
}

const GRID_MESH: ShapeSpec = {
  kind: 'mesh',
  positions: [0, 0, 0, 1, 0.1, 0, 2, 0, 0, 0, 0, 1, 1, 0.2, 1, 2, 0, 1, 0, 0, 2, 1, 0, 2, 2, 0.1, 2],
  indices: [0, 3, 1, 1, 3, 4, 1, 4, 2, 2, 4, 5, 3, 6, 4, 4, 6, 7, 4, 7, 5, 5, 7, 8],
};
const HULL_POINTS = [0, 0, 0, 0.5, 0, 0, 0, 0.5, 0, 0, 0, 0.5, 0.4, 0.4, 0.1, 0.1, 0.4, 0.4, 0.4, 0.1, 0.4, 0.3, 0.3, 0.3];

describe('physics-world memory', () => {
  afterAll(() => {
    if (process.env.PHYSICS_MEMORY_REPORT) console.log(`\n${figures.join('\n')}`);
  });

  it('frees everything each body factory allocates, over 10,000 cycles each', async () => {
    const w = await makeWorld();
    addGround(w);
    const cases: Array<[string, ShapeSpec, Parameters<PhysicsWorld['addShape']>[3]]> = [
      ['box', { kind: 'box', halfExtents: { x: 0.3, y: 0.2, z: 0.4 } }, {}],
      ['sphere', { kind: 'sphere', radius: 0.3 }, { motion: 'static' }],
      ['capsule', { kind: 'capsule', halfHeight: 0.3, radius: 0.2 }, { motion: 'kinematic' }],
      ['cylinder', { kind: 'cylinder', halfHeight: 0.3, radius: 0.2 }, { linearVelocity: { x: 0, y: -1, z: 0 } }],
      ['convex hull', { kind: 'convexHull', points: HULL_POINTS }, { motionQuality: 'linearCast' }],
      ['mesh', GRID_MESH, { motion: 'static' }],
      ['height field', { kind: 'heightField', heights: Array.from({ length: 64 }, (_, i) => (i % 7) * 0.1), sampleCount: 8, cellSize: 0.5 }, { motion: 'static' }],
      [
        'compound',
        {
          kind: 'compound',
          parts: [
            { shape: { kind: 'box', halfExtents: { x: 0.2, y: 0.2, z: 0.2 } } },
            { shape: { kind: 'sphere', radius: 0.2 }, position: { x: 0.4, y: 0, z: 0 } },
            { shape: { kind: 'convexHull', points: HULL_POINTS }, position: { x: -0.5, y: 0, z: 0 } },
          ],
        },
        { noCollideGroup: 3 },
      ],
    ];
    for (const [label, spec, opts] of cases) {
      const { before, after } = measure(w, label, bodyRound(w, spec, opts));
      expect(after, label).toBe(before);
    }
    expect(w.bodyCount).toBe(1);
    w.destroy();
  });

  it('frees sensor bodies and their open overlaps, with events flowing', async () => {
    const w = await makeWorld();
    addGround(w);
    const visitor = w.addBox({ x: 5, y: 0.2, z: 5 }, { x: 0, y: 0.2, z: 0 }, null, { allowSleeping: false });
    let events = 0;
    const round = (batch: number): void => {
      const sensors: BodyHandle[] = [];
      for (let i = 0; i < batch; i++) {
        sensors.push(w.addBox({ x: 0.2, y: 0.5, z: 0.2 }, { x: (i % 10) - 4.5, y: 0.5, z: Math.floor(i / 10) - 4.5 }, null, { motion: i % 2 ? 'static' : 'kinematic', sensor: { onEnter: () => events++ } }));
      }
      events += w.stepFixed().length;
      for (const s of sensors) w.removeBody(s); // each closes its overlap with an exit
      events += w.stepFixed().length;
    };
    const { before, after } = measure(w, 'sensor body', round);
    expect(after).toBe(before);
    expect(events).toBeGreaterThan(CYCLES * 2); // enter and exit per sensor (plus the callbacks)
    expect(w.sensorOverlaps(visitor)).toEqual([]);
    w.destroy();
  });

  it('frees every kind of constraint over 10,000 cycles', async () => {
    const w = await makeWorld();
    const a = w.addBox({ x: 0.2, y: 0.2, z: 0.2 }, { x: 0, y: 5, z: 0 }, null, { motion: 'static' });
    const b = w.addBox({ x: 0.2, y: 0.2, z: 0.2 }, { x: 1, y: 5, z: 0 });
    const pivot = { x: 0.5, y: 5, z: 0 };
    const axis = { x: 0, y: 0, z: 1 };
    let k = 0;
    const round = (batch: number): void => {
      const made = [];
      for (let i = 0; i < batch; i++, k++) {
        if (k % 4 === 0) made.push(w.pointLink(a, b, pivot));
        else if (k % 4 === 1) made.push(hingeLink(w, a, b, pivot, axis, { minRadians: -1, maxRadians: 1 }));
        else if (k % 4 === 2) made.push(distanceLink(w, a, b, a.position(), b.position(), { minDistance: 0.5, maxDistance: 2 }));
        else made.push(sliderLink(w, a, b, pivot, { x: 1, y: 0, z: 0 }, { minMetres: -1, maxMetres: 1 }));
      }
      w.stepFixed();
      for (const c of made) w.removeConstraint(c);
    };
    const { before, after } = measure(w, 'constraint', round);
    expect(after).toBe(before);
    expect(w.constraintCount).toBe(0);
    w.destroy();
  });

  it('frees characters (with their inner bodies) over 10,000 cycles', async () => {
    const w = await makeWorld();
    addGround(w);
    const round = (batch: number): void => {
      const chars: CharacterController[] = [];
      for (let i = 0; i < batch; i++) chars.push(new CharacterController(w, { position: { x: (i % 10) - 5, y: 0, z: Math.floor(i / 10) - 5 } }));
      w.stepFixed();
      for (const c of chars) {
        c.velocity.x = 1;
        c.move(1 / 60);
        c.destroy();
      }
    };
    const { before, after } = measure(w, 'character', round);
    expect(after).toBe(before);
    expect(w.bodyCount).toBe(1);
    w.destroy();
  });

  it('allocates nothing per ray cast', async () => {
    const w = await makeWorld();
    addGround(w);
    w.addSphere(0.5, { x: 0, y: 0.5, z: 0 }, { motion: 'static' });
    let hits = 0;
    const round = (batch: number): void => {
      for (let i = 0; i < batch; i++) {
        if (w.rayCast({ x: (i % 7) * 0.1, y: 5, z: 0 }, { x: 0, y: -10, z: 0.01 }, i % 2 === 0)) hits++;
        if (w.rayDownY(i % 5, 3, 0, 10) !== null) hits++;
      }
    };
    const { before, after } = measure(w, 'ray cast', round);
    expect(after).toBe(before);
    expect(hits).toBeGreaterThan(2 * CYCLES);
    w.destroy();
  });

  it('returns to the same free heap after clear(), every time', async () => {
    const w = await makeWorld();
    const scene = (batch: number): void => {
      addGround(w);
      const bodies: BodyHandle[] = [];
      for (let i = 0; i < batch; i++) bodies.push(w.addShape(i % 2 ? { kind: 'sphere', radius: 0.2 } : { kind: 'convexHull', points: HULL_POINTS }, { x: i % 10, y: 1 + Math.floor(i / 10), z: 0 }));
      for (let i = 1; i < 10; i++) w.pointLink(bodies[i - 1], bodies[i], bodies[i - 1].position());
      w.addBox({ x: 3, y: 1, z: 3 }, { x: 5, y: 1, z: 0 }, null, { motion: 'static', isSensor: true });
      for (let t = 0; t < 3; t++) w.stepFixed();
      w.clear();
    };
    const { before, after } = measure(w, 'clear()', scene, BATCH, 100 * BATCH); // 100 scenes of 100 bodies, each cleared
    expect(after).toBe(before);
    expect(w.bodyCount).toBe(0);
    expect(w.constraintCount).toBe(0);
    w.destroy();
  });

  it('leaks nothing across world create/destroy cycles', async () => {
    const probe = await makeWorld();
    const free = (): number => probe.jolt.JoltInterface.prototype.sGetFreeMemory();
    probe.destroy();
    const cycle = async (): Promise<void> => {
      const w = await makeWorld();
      addGround(w);
      const ch = new CharacterController(w, { position: { x: 0, y: 0, z: 0 } });
      w.addSphere(0.3, { x: 0, y: 2, z: 0 }, { sensor: {} });
      w.rayCast({ x: 0, y: 5, z: 0 }, { x: 0, y: -10, z: 0 });
      w.stepFixed();
      ch.move(1 / 60);
      w.destroy();
    };
    await cycle();
    const before = free();
    const cycles = 100;
    for (let i = 0; i < cycles; i++) await cycle();
    const after = free();
    figures.push(`${'world'.padEnd(14)} ${String(cycles).padStart(6)} cycles  free before ${before}  after ${after}  diff ${after - before}`);
    expect(after).toBe(before);
  });

  it('leaks only Jolt\'s type factory (under 4 KB) per world created while another one lives', async () => {
    // JoltInterface's constructor overwrites Jolt's global factory pointer without freeing the previous factory.
    const probe = await makeWorld();
    const free = (): number => probe.jolt.JoltInterface.prototype.sGetFreeMemory();
    probe.destroy();
    const overlapping = async (): Promise<void> => {
      const a = await makeWorld();
      const b = await makeWorld();
      a.destroy();
      b.destroy();
    };
    await overlapping();
    const before = free();
    for (let i = 0; i < 10; i++) await overlapping();
    const perPair = (before - free()) / 10;
    figures.push(`${'overlap'.padEnd(14)} ${String(10).padStart(6)} pairs   leak per world created beside another ${perPair} B`);
    expect(perPair).toBeGreaterThanOrEqual(0);
    expect(perPair).toBeLessThan(4096);
  });
});
