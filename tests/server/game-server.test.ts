// Tests for server/game-server.ts through the in-process harness: joining, moving, seeing each other in decoded
// snapshots, trigger events on both clients, leaving, late joiners, and decoded frames equal to the server's.
import { afterEach, describe, expect, it } from 'vitest';
import { ByeReason, CharacterQ, createSnapshotFormat, dequantizeAxis, framesEqual, quantizeFrame, readSnapshotHeader, type QuantizedFrame } from '../../shared/protocol/index.ts';
import { NEUTRAL_INPUT, type InputCommand } from '../../shared/sim/input.ts';
import { startHarness, type Harness, type TestClient } from './harness.ts';
import { emptyScenario, STREAM_ADD_TICK, STREAM_REMOVE_TICK, streamScenario, stripScenario, TRIGGER_MIN_X } from './test-scenarios.ts';

let h: Harness | null = null;
afterEach(async () => {
  await h?.close();
  h = null;
});

const walk = (moveX: number, moveZ = 0): InputCommand => ({ ...NEUTRAL_INPUT, moveX, moveZ });

/** Quantized feet x of a player in a decoded frame (undefined when absent). */
function charX(frame: QuantizedFrame, playerId: number): number | undefined {
  const i = Array.from(frame.playerIds).indexOf(playerId);
  return i < 0 ? undefined : frame.characters[i * 11 + CharacterQ.Px];
}

/** Sends `cmd` for the next `n` ticks, a few ticks ahead of the server, with redundancy, one message per tick. */
function drive(h: Harness, clients: Array<[TestClient, InputCommand]>, n: number): void {
  for (let i = 0; i < n; i++) {
    const next = h.room().sim.tick + 2;
    for (const [c, cmd] of clients) c.input(next, [cmd, cmd, cmd]);
    h.ticks(1);
  }
}

describe('GameServer (in-process)', () => {
  it('lets two clients join and each sees the other move in decoded snapshots', async () => {
    h = await startHarness({ scenarios: [stripScenario] });
    const a = await h.join('ann');
    const b = await h.join('bob');
    expect([a.playerId, b.playerId]).toEqual([1, 2]);
    expect(a.welcome?.staticBodies.length).toBe(2);
    h.ticks(10);
    const a0 = charX(b.latestFrame(), a.playerId)!;
    const b0 = charX(a.latestFrame(), b.playerId)!;
    drive(h, [[a, walk(127)], [b, walk(-127)]], 60);
    h.ticks(2);
    // A walked +x, B walked -x: each client's view of the other shows it.
    expect(charX(b.latestFrame(), a.playerId)! - a0).toBeGreaterThan(500); // > 1 m in 2 mm steps
    expect(charX(a.latestFrame(), b.playerId)! - b0).toBeLessThan(-500);
    expect(a.undecodable).toEqual([]);
  });

  it('decodes every snapshot into exactly the server\'s quantized state', async () => {
    h = await startHarness({ scenarios: [stripScenario], params: { boxes: 12 }, snapshotRateHz: 60 });
    const room = h.room();
    const format = createSnapshotFormat(stripScenario.bounds);
    const serverFrames = new Map<number, QuantizedFrame>();
    room.onTick((record) => serverFrames.set(record.tick, quantizeFrame(format, record.tick, room.sim.readBodyStates(), room.sim.characters())));
    const a = await h.join('ann');
    drive(h, [[a, walk(100, 50)]], 90);
    h.ticks(2);
    expect(a.frames.length).toBeGreaterThan(80);
    // The first snapshot is full, the rest are deltas against acked baselines.
    // A delta's 16-bit tick is completed from the previous snapshot's.
    let previousTick: number | null = null;
    const kinds = a.ofType('snapshot').map((m) => {
      const header = readSnapshotHeader(m.bytes, previousTick);
      previousTick = header.tick;
      return header.baselineTick === null;
    });
    expect(kinds[0]).toBe(true);
    expect(kinds.slice(1).every((full) => !full)).toBe(true);
    for (const f of a.frames) expect(framesEqual(f, serverFrames.get(f.tick)!), `tick ${f.tick}`).toBe(true);
  });

  it('delivers a trigger-zone event to both clients stamped with the tick it happened on', async () => {
    h = await startHarness({ scenarios: [stripScenario] });
    const serverEvents: Array<{ tick: number; type: string }> = [];
    h.room().onTick((_, events) => serverEvents.push(...events.filter((e) => e.type === 'sensorEnter')));
    const a = await h.join('ann');
    const b = await h.join('bob');
    drive(h, [[a, walk(127)]], 80); // 4 m/s: reaches x = 3 (minus the capsule radius) in under a second
    h.ticks(2);
    expect(serverEvents).toHaveLength(1);
    const enterA = a.events.filter((e) => e.type === 'sensorEnter');
    const enterB = b.events.filter((e) => e.type === 'sensorEnter');
    expect(enterA).toEqual(enterB);
    expect(enterA).toHaveLength(1);
    expect(enterA[0]).toMatchObject({ tick: serverEvents[0].tick, playerId: a.playerId });
    // In the snapshot just after that tick the character's capsule (radius 0.35 m) reaches the zone's edge.
    const format = createSnapshotFormat(stripScenario.bounds);
    const after = a.frames.find((f) => f.tick >= serverEvents[0].tick)!;
    const x = dequantizeAxis(format, 0, charX(after, a.playerId)!);
    expect(x + 0.35).toBeGreaterThanOrEqual(TRIGGER_MIN_X - 0.01);
    expect(x + 0.35).toBeLessThan(TRIGGER_MIN_X + 0.2);
  });

  it('removes a leaving player\'s character and tells the others', async () => {
    h = await startHarness({ scenarios: [stripScenario] });
    const a = await h.join('ann');
    const b = await h.join('bob');
    h.ticks(10);
    expect(Array.from(b.latestFrame().playerIds)).toEqual([1, 2]);
    a.send({ type: 'bye' });
    h.ticks(10);
    expect(Array.from(b.latestFrame().playerIds)).toEqual([2]);
    expect(b.events).toContainEqual(expect.objectContaining({ type: 'playerLeft', playerId: a.playerId }));
    expect(h.room().clientCount).toBe(1);
    const leaveRecord = h.history().records.find((r) => r.leaves.includes(a.playerId));
    expect(leaveRecord).toBeDefined();
  });

  it('delivers static bodies spawned after the welcome (streamed terrain) to clients in the room and to late joiners', async () => {
    h = await startHarness({ scenarios: [streamScenario] });
    const early = await h.join('early');
    expect(early.welcome?.staticBodies.map((d) => d.shape.kind)).toEqual(['box']);
    h.ticks(STREAM_ADD_TICK + 10);
    const tile = early.ofType('snapshot').flatMap((m) => m.descriptors).find((d) => d.motion === 'static');
    expect(tile).toMatchObject({ shape: { kind: 'box' }, position: { x: 5, y: 0.5, z: 5 } });
    expect(Array.from(early.latestFrame().bodyIds)).toContain(tile!.id);
    const late = await h.join('late');
    expect(late.welcome?.staticBodies.map((d) => d.id)).not.toContain(tile!.id);
    expect(late.welcome?.dynamicBodies.map((d) => d.id)).toContain(tile!.id);
    h.ticks(STREAM_REMOVE_TICK - STREAM_ADD_TICK);
    expect(Array.from(early.latestFrame().bodyIds)).not.toContain(tile!.id);
    expect(late.events).toContainEqual(expect.objectContaining({ type: 'bodyRemoved', bodyId: tile!.id }));
  });

  it('closes only the room whose tick throws; the other room and its players go on', async () => {
    h = await startHarness({ scenarios: [stripScenario, emptyScenario] });
    const a = await h.join('ann');
    const b = await h.join('bob', 'test-empty');
    const broken = h.room('test-empty');
    broken.sim.step = () => {
      throw new Error('injected tick fault');
    };
    const tickBefore = h.room().sim.tick;
    const framesBefore = a.frames.length;
    h.ticks(30);
    await h.settle(() => broken.closed);
    expect(broken.closed).toBe(true);
    expect(h.server.rooms.get('test-empty')).toBeUndefined();
    expect(b.ofType('bye')[0]).toMatchObject({ reason: ByeReason.RoomClosed, message: expect.stringMatching(/injected tick fault/) });
    h.ticks(30);
    expect(a.closed).toBeNull();
    expect(h.room().sim.tick).toBeGreaterThan(tickBefore + 50);
    expect(a.frames.length).toBeGreaterThan(framesBefore + 20);
  });

  it('refuses connections past the server\'s limit with a bye saying why', async () => {
    h = await startHarness({ scenarios: [stripScenario], maxConnections: 2 });
    await h.join('a');
    await h.join('b');
    const c = h.connect();
    h.ticks(1);
    expect(c.ofType('bye')).toEqual([expect.objectContaining({ reason: 'server-full' })]);
    expect(c.closed?.code).toBe(1013);
    expect(h.server.sessionCount()).toBe(2);
  });

  it('gives a late joiner a full snapshot of the current world', async () => {
    h = await startHarness({ scenarios: [stripScenario], params: { boxes: 6 } });
    const a = await h.join('ann');
    drive(h, [[a, walk(127)]], 120);
    const late = await h.join('lou');
    h.ticks(3);
    const first = late.ofType('snapshot')[0];
    expect(first).toBeDefined();
    const firstFrame = late.frames[0];
    // Full: every body and both characters, with descriptors for the characters' capsules it has not seen.
    expect(firstFrame.playerIds.length).toBe(2);
    expect(firstFrame.bodyIds.length).toBe(6 + 2);
    const sameTick = a.frames.find((f) => f.tick === firstFrame.tick);
    expect(sameTick && framesEqual(sameTick, firstFrame)).toBe(true);
    expect(late.welcome?.dynamicBodies.length).toBeGreaterThanOrEqual(6);
  });

  it('reports each open room\'s own 128 MiB WASM heap, and no longer a room that closed', async () => {
    h = await startHarness({ scenarios: [stripScenario] });
    await h.join('ann', 'test-strip');
    const heaps = h.server.roomHeaps();
    expect(heaps.map((r) => r.room)).toEqual(['default', 'test-strip']);
    for (const r of heaps) {
      expect(r.usedBytes).toBeGreaterThan(1024 * 1024);
      expect(r.usedBytes + r.freeBytes).toBe(128 * 1024 * 1024);
    }
    await h.room('test-strip').close('test over');
    expect(h.server.roomHeaps().map((r) => r.room)).toEqual(['default']);
  });
});
