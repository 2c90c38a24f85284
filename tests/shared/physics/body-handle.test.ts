// Tests of BodyHandle: getters return plain copies matching the bulk read bit for bit, the handle describes its body,
// and every accessor throws a clear Error once the body is gone.
import { describe, expect, it } from 'vitest';
import { BODY_STATE_STRIDE } from '../../../shared/physics/index.ts';
import { addGround, makeWorld, run } from '../../helpers/physics.ts';

describe('body-handle', () => {
  it('returns plain copies that do not follow the body or write back into it', async () => {
    const w = await makeWorld();
    const ball = w.addSphere(0.2, { x: 1, y: 5, z: 2 });
    const p = ball.position();
    p.y = 100;
    expect(ball.position().y).toBe(5);
    run(w, 10);
    expect(p.y).toBe(100); // the copy stays as it was
    expect(ball.position().y).toBeLessThan(5);
    expect(Object.keys(ball.rotation()).sort()).toEqual(['w', 'x', 'y', 'z']);
    w.destroy();
  });

  it('reads the same bits through readStateInto, the getters and the bulk read', async () => {
    const w = await makeWorld();
    addGround(w);
    const box = w.addBox({ x: 0.3, y: 0.2, z: 0.1 }, { x: 0.1, y: 2, z: 0 }, { x: 0.2, y: 0.1, z: 0, w: Math.sqrt(1 - 0.05) }, { angularVelocity: { x: 1, y: 2, z: 3 } });
    run(w, 37);
    const mine = new Float32Array(BODY_STATE_STRIDE);
    box.readStateInto(mine, 0);
    const p = box.position();
    const q = box.rotation();
    const v = box.linearVelocity();
    const a = box.angularVelocity();
    expect(Array.from(mine)).toEqual([p.x, p.y, p.z, q.x, q.y, q.z, q.w, v.x, v.y, v.z, a.x, a.y, a.z]);
    const bulk = w.readBodyStates();
    const i = Array.from(bulk.ids).indexOf(box.id);
    expect(Array.from(bulk.states.subarray(i * BODY_STATE_STRIDE, (i + 1) * BODY_STATE_STRIDE))).toEqual(Array.from(mine));
    w.destroy();
  });

  it('describes its body: id, shape, motion, layer, mask, sensor-ness and role', async () => {
    const w = await makeWorld();
    const zone = w.addBox({ x: 1, y: 2, z: 3 }, { x: 0, y: 0, z: 0 }, null, { motion: 'static', isSensor: true, name: 'zone' });
    expect(zone.id).toBe(1);
    expect(zone.shape).toEqual({ kind: 'box', halfExtents: { x: 1, y: 2, z: 3 } });
    expect(zone.motion).toBe('static');
    expect(zone.isSensor).toBe(true);
    expect(zone.role).toBe('body');
    expect(zone.name).toBe('zone');
    expect(zone.isActive()).toBe(true); // a sensor stays awake so it can see sleeping bodies
    w.destroy();
  });

  it('throws a clear Error from every accessor once its body is removed', async () => {
    const w = await makeWorld();
    const ball = w.addSphere(0.2, { x: 0, y: 0, z: 0 }, { name: 'marble' });
    w.removeBody(ball);
    const out = new Float32Array(BODY_STATE_STRIDE);
    for (const read of [() => ball.position(), () => ball.rotation(), () => ball.linearVelocity(), () => ball.angularVelocity(), () => ball.isActive(), () => ball.readStateInto(out, 0)]) {
      expect(read).toThrow(/body 1 \(marble\) was removed/);
    }
    w.destroy();
  });
});
