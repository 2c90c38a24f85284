// Tests of the interpolation buffer with synthetic snapshot streams: in order, late, early, duplicated, reordered and
// with gaps; lerp/slerp between the snapshots around the render time, bounded extrapolation then hold, spawns and
// removals at their tick, and a delay that adapts to arrival jitter.
import { describe, expect, it } from 'vitest';
import { InterpolationBuffer, slerpInto, type InterpolatedFrame } from '../../sdk/interpolation.ts';
import type { SnapshotView } from '../../shared/protocol/snapshot-frame.ts';
import { Prng } from '../../shared/sim/prng.ts';
import type { CharacterState } from '../../shared/sim/types.ts';
import { TICK_MS } from '../../shared/tick-rate.ts';


/** Body 1 moves +1 m/tick along x and spins about y at 0.05 rad/tick; body 2 sits still; character 7 walks along z. */
function snap(tick: number, opts: { ids?: number[] } = {}): SnapshotView {
  const ids = opts.ids ?? [1, 2];
  const positions = new Float32Array(ids.length * 3);
  const rotations = new Float32Array(ids.length * 4);
  ids.forEach((id, i) => {
    positions.set(id === 1 ? [tick, 1, 0] : [id, 0, 5], i * 3);
    const half = id === 1 ? (0.05 * tick) / 2 : 0;
    rotations.set([0, Math.sin(half), 0, Math.cos(half)], i * 4);
  });
  const character: CharacterState = { playerId: 7, bodyId: 99, position: { x: 0, y: 0, z: tick * 0.1 }, velocity: { x: 0, y: 0, z: 6 }, yaw: (tick * 0.1) % (2 * Math.PI), pitch: 0, groundState: 'ground', buttons: 0 };
  return { tick, ids: Uint32Array.from(ids), positions, rotations, atRest: new Uint8Array(ids.length), characters: [character] };
}

function xOf(f: InterpolatedFrame, id = 1): number {
  const i = Array.from(f.view!.ids).indexOf(id);
  return f.view!.positions[i * 3];
}

/** A buffer for 20 Hz snapshots (every 3 ticks) fed on schedule: snapshot t arrives at t·TICK_MS + 50 ms. */
function steadyBuffer(lastTick: number, opts: Partial<ConstructorParameters<typeof InterpolationBuffer>[0]> = {}): InterpolationBuffer {
  const buf = new InterpolationBuffer({ tickRateHz: 60, snapshotRateHz: 20, ...opts });
  for (let t = 0; t <= lastTick; t += 3) buf.push(snap(t), t * TICK_MS + 50);
  return buf;
}

describe('interpolation', () => {
  it('renders two snapshot intervals behind the arrivals and lerps positions between the snapshots around it', () => {
    const buf = steadyBuffer(60);
    const now = 60.5 * TICK_MS + 50;
    const f = buf.sample(now);
    // Render tick = arrival-time tick − 2 × 3 ticks (no jitter): 54.5, between snapshots 54 and 57.
    expect(f.mode).toBe('interpolating');
    expect(f.renderTick).toBeCloseTo(54.5, 6);
    expect(f.targetDelayMs).toBeCloseTo(100, 6);
    expect(f.delayMs).toBeCloseTo(100, 6);
    expect(xOf(f)).toBeCloseTo(54.5, 4);
    expect(f.bufferDepth).toBe(2);
    const g = buf.sample(now + 1.5 * TICK_MS);
    expect(g.renderTick).toBeCloseTo(56, 6);
    expect(xOf(g)).toBeCloseTo(56, 4);
    expect(xOf(g, 2)).toBe(2);
  });

  it('slerps rotations on the shortest path, also when the stored signs flip', () => {
    const a = new Float32Array([0, Math.sin(0.1), 0, Math.cos(0.1)]);
    const b = new Float32Array([0, -Math.sin(0.3), 0, -Math.cos(0.3)]); // the same rotation as +0.6 rad, negated
    const out = new Float32Array(4);
    slerpInto(a, 0, b, 0, 0.5, out, 0);
    // Halfway between 0.2 rad and 0.6 rad about y is 0.4 rad (half-angle 0.2), not the long way round.
    expect(Math.abs(out[1])).toBeCloseTo(Math.sin(0.2), 5);
    expect(Math.abs(out[3])).toBeCloseTo(Math.cos(0.2), 5);
    const buf = steadyBuffer(30);
    const f = buf.sample(30 * TICK_MS + 50 + TICK_MS);
    const i = Array.from(f.view!.ids).indexOf(1);
    const angle = 2 * Math.atan2(f.view!.rotations[i * 4 + 1], f.view!.rotations[i * 4 + 3]);
    expect(angle).toBeCloseTo(0.05 * f.renderTick, 4);
  });

  it('interpolates characters: position, shortest-arc yaw, discrete fields from the older snapshot', () => {
    const buf = steadyBuffer(30);
    const f = buf.sample(30 * TICK_MS + 50);
    const c = f.view!.characters[0];
    expect(c.playerId).toBe(7);
    expect(c.position.z).toBeCloseTo(f.renderTick * 0.1, 5);
    expect(c.yaw).toBeCloseTo(f.renderTick * 0.1, 5);
    expect(c.groundState).toBe('ground');
  });

  it('extrapolates for at most the configured time when snapshots stop, then holds', () => {
    const buf = steadyBuffer(30, { maxExtrapolationMs: 100 });
    // Newest is tick 30; render tick 24 now. 8 ticks later the render tick is 32: 2 ticks past the newest.
    let f = buf.sample(30 * TICK_MS + 50);
    f = buf.sample(38 * TICK_MS + 50);
    expect(f.mode).toBe('extrapolating');
    expect(f.extrapolatedTicks).toBeCloseTo(2, 5);
    expect(xOf(f)).toBeCloseTo(32, 3);
    // Much later: capped at 100 ms = 6 ticks past tick 30, then held still.
    f = buf.sample(60 * TICK_MS + 50);
    expect(f.mode).toBe('holding');
    expect(xOf(f)).toBeCloseTo(36, 3);
    const later = buf.sample(90 * TICK_MS + 50);
    expect(xOf(later)).toBeCloseTo(36, 3);
    expect(xOf(later, 2)).toBe(2);
  });

  it('does not extrapolate bodies at rest', () => {
    const buf = new InterpolationBuffer({ tickRateHz: 60, snapshotRateHz: 20 });
    for (let t = 0; t <= 12; t += 3) {
      const s = snap(t);
      s.atRest[0] = t >= 9 ? 1 : 0;
      buf.push(s, t * TICK_MS + 50);
    }
    buf.sample(12 * TICK_MS + 50);
    const f = buf.sample(20 * TICK_MS + 50);
    expect(f.mode).toBe('extrapolating');
    expect(xOf(f)).toBe(12);
  });

  it('holds the first snapshot until the render time reaches it (early arrivals wait in the buffer)', () => {
    const buf = new InterpolationBuffer({ tickRateHz: 60, snapshotRateHz: 20 });
    buf.push(snap(100), 1000);
    const f = buf.sample(1000);
    expect(f.mode).toBe('waiting');
    expect(f.renderTick).toBeCloseTo(94, 6);
    expect(xOf(f)).toBe(100);
    // Snapshots that arrive early (before the render time reaches them) are just buffered ahead.
    buf.push(snap(103), 1000 + 3 * TICK_MS - 20);
    buf.push(snap(106), 1000 + 6 * TICK_MS - 20);
    const g = buf.sample(1000 + 7 * TICK_MS);
    expect(g.mode).toBe('interpolating');
    expect(g.bufferDepth).toBeGreaterThanOrEqual(1);
  });

  it('ignores duplicates and gives the same output for reordered arrivals as for in-order ones', () => {
    const inOrder = new InterpolationBuffer({ tickRateHz: 60, snapshotRateHz: 20 });
    const shuffled = new InterpolationBuffer({ tickRateHz: 60, snapshotRateHz: 20 });
    const ticks = [0, 3, 6, 9, 12, 15, 18, 21];
    for (const t of ticks) inOrder.push(snap(t), t * TICK_MS + 50);
    // Same arrival times per snapshot, but 9 arrives after 12 and 18 twice.
    const order = [0, 3, 6, 12, 9, 15, 18, 18, 21];
    const outcomes = order.map((t) => shuffled.push(snap(t), t * TICK_MS + 50));
    expect(outcomes.filter((o) => o === 'duplicate')).toHaveLength(1);
    expect(shuffled.stats).toMatchObject({ stored: 8, duplicates: 1, reordered: 1 });
    for (const now of [21 * TICK_MS + 50, 22 * TICK_MS + 50, 23 * TICK_MS + 50]) {
      const a = inOrder.sample(now);
      const b = shuffled.sample(now);
      expect(b.renderTick).toBeCloseTo(a.renderTick, 9);
      expect(Array.from(b.view!.positions)).toEqual(Array.from(a.view!.positions));
    }
  });

  it('drops snapshots older than the one under the render time as late', () => {
    const buf = steadyBuffer(30);
    buf.sample(30 * TICK_MS + 50);
    expect(buf.push(snap(10), 30 * TICK_MS + 60)).toBe('late');
    expect(buf.stats.late).toBe(1);
  });

  it('interpolates across a gap of missing snapshots', () => {
    const buf = new InterpolationBuffer({ tickRateHz: 60, snapshotRateHz: 20 });
    for (const t of [0, 3, 6, 18, 21, 24, 27]) buf.push(snap(t), t * TICK_MS + 50);
    // Render tick 12 lies between 6 and 18.
    const f = buf.sample(18 * TICK_MS + 50);
    expect(f.renderTick).toBeCloseTo(12, 6);
    expect(f.mode).toBe('interpolating');
    expect(xOf(f)).toBeCloseTo(12, 4);
  });

  it('shows a spawned body from the snapshot it first appears in and a removed one until the snapshot it is gone from', () => {
    const buf = new InterpolationBuffer({ tickRateHz: 60, snapshotRateHz: 20 });
    for (let t = 0; t <= 30; t += 3) buf.push(snap(t, { ids: t < 15 ? [1, 2] : t < 24 ? [1, 2, 3] : [1, 3] }), t * TICK_MS + 50);
    const idsAt = (renderTick: number): number[] => Array.from(buf.sample(renderTick * TICK_MS + 50 + 100).view!.ids);
    expect(idsAt(14.9)).toEqual([1, 2]);
    expect(idsAt(15.1)).toEqual([1, 2, 3]);
    expect(idsAt(23.9)).toEqual([1, 2, 3]);
    expect(idsAt(24.1)).toEqual([1, 3]);
  });

  it('raises the delay with arrival jitter and steers the render tick smoothly, never backwards', () => {
    const rng = new Prng(3);
    const calm = steadyBuffer(90);
    const jittery = new InterpolationBuffer({ tickRateHz: 60, snapshotRateHz: 20 });
    for (let t = 0; t <= 90; t += 3) jittery.push(snap(t), t * TICK_MS + 50 + rng.range(0, 60));
    expect(calm.targetDelayMs).toBeCloseTo(100, 6);
    expect(jittery.targetDelayMs).toBeGreaterThan(140);
    expect(jittery.targetDelayMs).toBeLessThan(100 + 60);
    // Keep feeding jittery arrivals and sample every 16 ms: the render tick only moves forward, at 0.9–1.1× speed.
    let prev = jittery.sample(90 * TICK_MS + 60).renderTick;
    let t = 93;
    for (let ms = 90 * TICK_MS + 76; ms < 180 * TICK_MS; ms += 16) {
      while (t * TICK_MS + 50 <= ms) {
        jittery.push(snap(t), t * TICK_MS + 50 + rng.range(0, 60));
        t += 3;
      }
      const f = jittery.sample(ms);
      const advanced = f.renderTick - prev;
      expect(advanced).toBeGreaterThanOrEqual((16 / TICK_MS) * 0.9 - 1e-9);
      expect(advanced).toBeLessThanOrEqual((16 / TICK_MS) * 1.1 + 1e-9);
      prev = f.renderTick;
      expect(f.mode === 'interpolating' || f.mode === 'extrapolating').toBe(true);
    }
  });

  it('returns an empty frame before any snapshot and starts over after reset', () => {
    const buf = steadyBuffer(9);
    buf.reset();
    expect(buf.sample(0)).toMatchObject({ view: null, mode: 'empty', bufferDepth: 0 });
    expect(() => new InterpolationBuffer({ tickRateHz: 0, snapshotRateHz: 20 })).toThrow(/must be > 0/);
  });
});
