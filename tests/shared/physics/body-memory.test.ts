// Tests of the direct heap reads of moving bodies: the installed Jolt build's Body layout passes the check (so the
// world's reads really skip the getters), what a world reads equals every body's getters bit for bit, and shapes
// centred on their origin read their position without the getter.
import { describe, expect, it } from 'vitest';
import { BODY_STATE_STRIDE } from '../../../shared/physics/index.ts';
import { BodyMemory, BodyReadMode } from '../../../shared/physics/body-memory.ts';
import { makeWorld, run } from '../../helpers/physics.ts';

/** A float's bits (so -0 and NaN payloads count). */
function bits(x: number): number {
  const f = new Float32Array([x]);
  return new Uint32Array(f.buffer)[0];
}

describe('body-memory', () => {
  it("reads every moving body as its getters do, bit for bit, with the build's offsets trusted", async () => {
    const w = await makeWorld();
    w.addBox({ x: 10, y: 0.5, z: 10 }, { x: 0, y: -0.5, z: 0 }, null, { motion: 'static' });
    for (let i = 0; i < 40; i++) {
      const at = { x: (i % 8) * 0.9 - 3.5, y: 1 + Math.floor(i / 8), z: (i % 3) * 0.4 };
      const spin = { angularVelocity: { x: i % 5, y: 1, z: -(i % 3) } };
      if (i % 4 === 0) w.addConvexHull([0, 0, 0, 0.5, 0, 0, 0, 0.7, 0, 0, 0, 0.4], at, null, spin);
      else if (i % 4 === 1) w.addSphere(0.3, at, spin);
      else if (i % 4 === 2) w.addCapsule(0.3, 0.2, at, null, spin);
      else w.addBox({ x: 0.3, y: 0.2, z: 0.25 }, at, null, { ...spin, motion: i % 8 === 3 ? 'kinematic' : 'dynamic' });
    }
    for (let t = 0; t < 40; t++) {
      run(w, 1);
      const s = w.readBodyStates();
      for (let i = 0; i < s.count; i++) {
        const h = w.getBody(s.ids[i])!;
        const p = h.position();
        const q = h.rotation();
        const v = h.linearVelocity();
        const a = h.angularVelocity();
        const expected = [p.x, p.y, p.z, q.x, q.y, q.z, q.w, v.x, v.y, v.z, a.x, a.y, a.z].map(bits);
        const got = Array.from(s.states.subarray(i * BODY_STATE_STRIDE, (i + 1) * BODY_STATE_STRIDE), bits);
        if (got.join() !== expected.join()) expect.fail(`tick ${t}: body ${s.ids[i]} read ${got} but its getters give ${expected}`);
      }
    }
    expect(BodyMemory.of(w.jolt)?.enabled).toBe(true);
    w.destroy();
  });

  it('reads a body centred on its origin without the position getter, and a hull through it', async () => {
    const w = await makeWorld();
    const box = w.addBox({ x: 0.5, y: 0.5, z: 0.5 }, { x: 1, y: 2, z: 3 });
    const hull = w.addConvexHull([0, 0, 0, 1, 0, 0, 0, 1, 0, 0, 0, 1], { x: -1, y: 2, z: 3 });
    const memory = BodyMemory.of(w.jolt)!;
    const ptr = (id: number): number => w.jolt.getPointer(w.getBody(id)!.raw);
    expect(memory.modeFor(ptr(box.id))).toBe(BodyReadMode.Direct);
    expect(memory.modeFor(ptr(hull.id))).toBe(BodyReadMode.DirectPoseFromGetter);
    w.destroy();
  });
});
