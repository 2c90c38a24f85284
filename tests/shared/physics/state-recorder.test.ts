// Tests of Jolt state I/O: the byte form and the fast in-memory form both rewind a world so it replays bit for bit;
// short or garbage bytes fail without harming the module; neither form leaks.
import { describe, expect, it } from 'vitest';
import { FastStateBuffer, restoreStateBytes, saveStateBytes, type PhysicsWorld } from '../../../shared/physics/index.ts';
import { addGround, ballast, makeWorld } from '../../helpers/physics.ts';

async function pile(): Promise<PhysicsWorld> {
  const w = await makeWorld();
  addGround(w);
  for (let i = 0; i < 40; i++) {
    const pos = { x: (i % 5) * 0.45 - 1, y: 0.5 + Math.floor(i / 5) * 0.45, z: (i % 3) * 0.1 };
    if (i % 2) w.addBox({ x: 0.2, y: 0.2, z: 0.2 }, pos);
    else w.addSphere(0.2, pos, { restitution: 0.5 });
  }
  for (let t = 0; t < 20; t++) w.stepFixed();
  return w;
}

/** Steps `ticks` ticks and returns a copy of every tick's bulk state. */
function trace(w: PhysicsWorld, ticks: number): Float32Array[] {
  const out: Float32Array[] = [];
  for (let t = 0; t < ticks; t++) {
    w.stepFixed();
    out.push(w.readBodyStates().states.slice());
  }
  return out;
}

describe('state-recorder', () => {
  it('rewinds a world from bytes so it replays the same states bit for bit', async () => {
    const w = await pile();
    const J = w.jolt;
    const bytes = saveStateBytes(J, (r) => w.system.SaveState(r, J.EStateRecorderState_All));
    expect(bytes.length).toBeGreaterThan(40 * 13 * 4);
    const first = trace(w, 60);
    expect(restoreStateBytes(J, bytes, (r) => w.system.RestoreState(r))).toBe(true);
    expect(trace(w, 60)).toEqual(first);
    // Restoring into a second world built the same way gives the same future too.
    const other = await pile();
    expect(restoreStateBytes(J, bytes, (r) => other.system.RestoreState(r))).toBe(true);
    expect(trace(other, 60)).toEqual(first);
    w.destroy();
    other.destroy();
  });

  it('rewinds through the fast in-memory buffer, and tells equal states apart from different ones', async () => {
    const w = await pile();
    const J = w.jolt;
    const a = new FastStateBuffer(J);
    const b = new FastStateBuffer(J);
    a.save((r) => w.system.SaveState(r, J.EStateRecorderState_All));
    b.save((r) => w.system.SaveState(r, J.EStateRecorderState_All));
    expect(a.isEqual(b)).toBe(true);
    const first = trace(w, 45);
    b.save((r) => w.system.SaveState(r, J.EStateRecorderState_All));
    expect(a.isEqual(b)).toBe(false);
    expect(a.restore((r) => w.system.RestoreState(r))).toBe(true);
    expect(trace(w, 45)).toEqual(first);
    expect(a.restore((r) => w.system.RestoreState(r))).toBe(true); // restorable again and again
    expect(trace(w, 45)).toEqual(first);
    a.dispose();
    b.dispose();
    a.dispose(); // idempotent
    expect(() => a.save(() => {})).toThrow(/FastStateBuffer was disposed/);
    w.destroy();
  });

  it('reports truncated bytes as a failed restore, and the world can still be restored and stepped', async () => {
    const w = await pile();
    const J = w.jolt;
    const bytes = saveStateBytes(J, (r) => w.system.SaveState(r, J.EStateRecorderState_All));
    const first = trace(w, 30);
    for (const cut of [0, 1, 7, Math.floor(bytes.length / 2), bytes.length - 1]) {
      expect(restoreStateBytes(J, bytes.subarray(0, cut), (r) => w.system.RestoreState(r)), `cut at ${cut}`).toBe(false);
    }
    expect(restoreStateBytes(J, bytes, (r) => w.system.RestoreState(r))).toBe(true);
    expect(trace(w, 30)).toEqual(first);
    w.destroy();
  });

  it('survives garbage bytes without aborting the module (the bytes carry no checksum of their own)', async () => {
    const w = await pile();
    const J = w.jolt;
    const good = saveStateBytes(J, (r) => w.system.SaveState(r, J.EStateRecorderState_All));
    let seed = 12345;
    const rnd = (): number => {
      seed = (seed * 48271) % 2147483647;
      return seed / 2147483647;
    };
    for (let trial = 0; trial < 60; trial++) {
      const bad = good.slice();
      if (trial % 2) for (let k = 0; k < bad.length; k++) bad[k] = Math.floor(rnd() * 256);
      else for (let k = 0; k < 6; k++) bad[Math.floor(rnd() * bad.length)] ^= 1 << Math.floor(rnd() * 8);
      restoreStateBytes(J, bad, (r) => w.system.RestoreState(r)); // may succeed with nonsense: callers checksum
      w.stepFixed();
    }
    expect(restoreStateBytes(J, good, (r) => w.system.RestoreState(r))).toBe(true);
    const ball = w.addSphere(0.2, { x: 3, y: 2, z: 3 });
    for (let t = 0; t < 30; t++) w.stepFixed();
    expect(ball.position().y).toBeLessThan(2);
    w.destroy();
  });

  it('leaks nothing over 1,000 saves and restores in either form', async () => {
    const w = await pile();
    const J = w.jolt;
    const cycle = (): void => {
      const buf = new FastStateBuffer(J);
      buf.save((r) => w.system.SaveState(r, J.EStateRecorderState_All));
      buf.restore((r) => w.system.RestoreState(r));
      buf.dispose();
      const bytes = saveStateBytes(J, (r) => w.system.SaveState(r, J.EStateRecorderState_All));
      restoreStateBytes(J, bytes, (r) => w.system.RestoreState(r));
      w.stepFixed();
    };
    cycle();
    const before = w.freeHeapBytes();
    for (let i = 0; i < 1000; i++) cycle();
    expect(w.freeHeapBytes()).toBe(before);
    w.destroy();
  });

  it('saves a whole world with saveWorld only when the heap can hold it, refusing with a clear Error otherwise', async () => {
    const w = await pile();
    const buf = new FastStateBuffer(w.jolt);
    const need = w.stateSaveHeapBytes();
    expect(need).toBeGreaterThan(41 * 1200);
    const release = ballast(w, w.minFreeHeapBytes + need - 4096);
    try {
      expect(() => buf.saveWorld(w)).toThrow(/FastStateBuffer.saveWorld: the WASM heap is nearly full \(\d+\.\d MiB free, ~0\.\d MiB needed, 8\.0 MiB kept in reserve/);
      w.stepFixed(); // the world is unharmed
    } finally {
      release();
    }
    buf.saveWorld(w);
    const first = trace(w, 20);
    expect(buf.restoreWorld(w)).toBe(true);
    expect(trace(w, 20)).toEqual(first);
    buf.dispose();
    w.destroy();
  });
});
