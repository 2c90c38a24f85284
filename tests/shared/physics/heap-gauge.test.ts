// Tests of the free-heap gauge: spawns and state-save checks far from the reserve read the heap only every
// REFRESH_EVERY grants, near the reserve every spawn reads it exactly, and worlds on one module share one gauge.
import { describe, expect, it } from 'vitest';
import { heapGaugeOf, REFRESH_EVERY, SLACK_BYTES } from '../../../shared/physics/heap-gauge.ts';
import { ballast, makeWorld } from '../../helpers/physics.ts';

describe('heap-gauge', () => {
  it('reads the heap once per REFRESH_EVERY spawns while the heap is far from full', async () => {
    const w = await makeWorld();
    const gauge = heapGaugeOf(w.jolt);
    const before = gauge.exactReads;
    for (let i = 0; i < 1000; i++) w.removeBody(w.addSphere(0.1, { x: 0, y: 10, z: 0 }));
    const reads = gauge.exactReads - before;
    expect(reads).toBeGreaterThanOrEqual(Math.floor(1000 / REFRESH_EVERY));
    expect(reads).toBeLessThanOrEqual(Math.ceil(1000 / REFRESH_EVERY) + 1);
    w.destroy();
  });

  it('checks room for state saves from the estimate too while the heap is far from full', async () => {
    const w = await makeWorld();
    for (let i = 0; i < 50; i++) w.addSphere(0.1, { x: i, y: 10, z: 0 });
    const gauge = heapGaugeOf(w.jolt);
    const before = gauge.exactReads;
    for (let i = 0; i < 200; i++) w.ensureRoomForStateSave('save');
    expect(gauge.exactReads - before).toBeLessThanOrEqual(Math.ceil(200 / REFRESH_EVERY) + 1);
    w.destroy();
  });

  it('reads the heap on every spawn once the estimate nears the reserve', async () => {
    const w = await makeWorld({ minFreeHeapBytes: 1024 * 1024 });
    const gauge = heapGaugeOf(w.jolt);
    const release = ballast(w, 1024 * 1024 + SLACK_BYTES / 2);
    try {
      const before = gauge.exactReads;
      for (let i = 0; i < 10; i++) w.removeBody(w.addSphere(0.1, { x: 0, y: 10, z: 0 }));
      expect(gauge.exactReads - before).toBe(10);
    } finally {
      release();
    }
    w.destroy();
  });

  it('is shared by every world on one module, so one world\'s spawns count against the other\'s estimate', async () => {
    const a = await makeWorld();
    const b = await makeWorld();
    expect(a.jolt).toBe(b.jolt);
    expect(heapGaugeOf(a.jolt)).toBe(heapGaugeOf(b.jolt));
    a.destroy();
    b.destroy();
  });
});
