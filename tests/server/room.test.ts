// Tests for server/room.ts with a recording stand-in simulation: the exact records stepped (joins, leaves, inputs
// applied or repeated), event and frame delivery, limits, pausing when empty, failure isolation, held players.
import { describe, expect, it } from 'vitest';
import { OfferResult } from '../../server/input-buffer.ts';
import { silentLogger } from '../../server/logger.ts';
import { createMetrics, type ServerMetrics } from '../../server/metrics.ts';
import { Room, RoomError, type BodyStates, type RoomMember, type RoomOptions, type RoomSimulation, type WorldFrame } from '../../server/room.ts';
import { ManualClock } from '../../shared/clock.ts';
import { NEUTRAL_INPUT, type InputCommand } from '../../shared/sim/input.ts';
import type { BodyDescriptor, CharacterState, SimEvent, TickInputRecord } from '../../shared/sim/types.ts';
import { TICK_MS } from '../../shared/tick-rate.ts';

// A stand-in simulation: remembers every record, reports a join/leave event per player, one body per player.
class FakeSim implements RoomSimulation {
  tick = 0;
  readonly records: TickInputRecord[] = [];
  readonly players = new Set<number>();
  destroyed = false;
  failOnTick = -1;

  step(record: TickInputRecord): SimEvent[] {
    if (record.tick !== this.tick) throw new Error(`fake sim: got tick ${record.tick}, at ${this.tick}`);
    if (record.tick === this.failOnTick) throw new Error('fake sim exploded');
    this.records.push(structuredClone(record));
    const events: SimEvent[] = [];
    for (const id of record.leaves) {
      this.players.delete(id);
      events.push({ type: 'playerLeft', tick: record.tick, playerId: id });
    }
    for (const j of record.joins) {
      this.players.add(j.playerId);
      events.push({ type: 'playerJoined', tick: record.tick, playerId: j.playerId, name: j.name });
    }
    this.tick++;
    return events;
  }
  stateHash(): string {
    return this.tick.toString(16).padStart(16, '0');
  }
  characters(): CharacterState[] {
    return [];
  }
  readBodyStates(): BodyStates {
    const ids = Uint32Array.from([...this.players].sort((a, b) => a - b));
    return { count: ids.length, ids, states: new Float32Array(ids.length * 13), flags: new Uint8Array(ids.length) };
  }
  staticDescriptors() {
    return [];
  }
  bodyDescriptor(_id: number): BodyDescriptor | undefined {
    return undefined;
  }
  destroy(): void {
    this.destroyed = true;
  }
}

class Member implements RoomMember {
  readonly events: Array<[number, readonly SimEvent[]]> = [];
  readonly frames: WorldFrame[] = [];
  closedWith: string | null = null;
  removedWith: string | null = null;
  throwOnFrame = false;
  deliverEvents(tick: number, events: readonly SimEvent[]): void {
    this.events.push([tick, events]);
  }
  deliverFrame(frame: WorldFrame): void {
    if (this.throwOnFrame) throw new Error('member broke');
    this.frames.push(frame);
  }
  roomClosed(reason: string): void {
    this.closedWith = reason;
  }
  removed(reason: string): void {
    this.removedWith = reason;
  }
}

const cmd = (moveX: number): InputCommand => ({ ...NEUTRAL_INPUT, moveX });

function makeRoom(over: Partial<RoomOptions> = {}): { room: Room; sim: FakeSim; clock: ManualClock; metrics: ServerMetrics } {
  const sim = new FakeSim();
  const clock = new ManualClock();
  const metrics = createMetrics({ processMetrics: false });
  const room = new Room(sim, {
    id: 'r',
    scenarioName: 'fake',
    params: {},
    seed: 1,
    clock,
    metrics,
    logger: silentLogger(),
    snapshotRateHz: 30,
    maxClients: 4,
    maxBodies: 100,
    ...over,
  });
  room.start();
  return { room, sim, clock, metrics };
}

describe('Room', () => {
  it('puts a join in the next record and applies the player\'s inputs from the tick after', () => {
    const { room, sim, clock } = makeRoom();
    const a = new Member();
    const joined = room.join(a, 'ann');
    expect(joined).toEqual({ playerId: 1, joinTick: 0, firstInputTick: 1 });
    room.offerInput(1, 1, cmd(10));
    room.offerInput(1, 3, cmd(30));
    clock.advance(3 * TICK_MS);
    expect(sim.records).toEqual([
      { tick: 0, leaves: [], joins: [{ playerId: 1, name: 'ann' }], commands: [] },
      { tick: 1, leaves: [], joins: [], commands: [{ playerId: 1, input: cmd(10) }] },
      { tick: 2, leaves: [], joins: [], commands: [{ playerId: 1, input: cmd(10) }] },
      { tick: 3, leaves: [], joins: [], commands: [{ playerId: 1, input: cmd(30) }] },
    ]);
    expect(a.events[0]).toEqual([0, [{ type: 'playerJoined', tick: 0, playerId: 1, name: 'ann' }]]);
  });

  it('drops inputs for ticks already applied and keeps commands sorted by player', () => {
    const { room, sim, clock } = makeRoom();
    room.join(new Member(), 'a');
    room.join(new Member(), 'b');
    clock.advance(2 * TICK_MS);
    expect(room.offerInput(2, 1, cmd(5))).toBe(OfferResult.Late);
    room.offerInput(2, 3, cmd(7));
    room.offerInput(1, 3, cmd(8));
    clock.advance(TICK_MS);
    expect(sim.records[3].commands).toEqual([
      { playerId: 1, input: cmd(8) },
      { playerId: 2, input: cmd(7) },
    ]);
    expect(room.offerInput(99, 4, cmd(1))).toBeNull();
  });

  it('offers a message\'s commands tick by tick, tallying those too late and too far ahead', () => {
    const { room, sim, clock } = makeRoom();
    room.join(new Member(), 'a');
    clock.advance(3 * TICK_MS);
    const tally = { inputsLate: 0, inputsTooFar: 0 };
    const next = sim.records.length; // the first tick not yet run
    room.offerInputs(1, next - 2, [cmd(1), cmd(2), cmd(3), cmd(4)], tally);
    room.offerInputs(1, 10_000, [cmd(9)], tally);
    room.offerInputs(99, 4, [cmd(9)], tally); // a player no longer in the room: nothing
    expect(tally).toEqual({ inputsLate: 2, inputsTooFar: 1 });
    clock.advance(2 * TICK_MS);
    expect(sim.records.slice(next, next + 2).map((r) => r.commands)).toEqual([[{ playerId: 1, input: cmd(3) }], [{ playerId: 1, input: cmd(4) }]]);
  });

  it('records a leave on the next tick, and a join that never reached a record leaves no trace', () => {
    const { room, sim, clock } = makeRoom();
    room.join(new Member(), 'a');
    clock.advance(TICK_MS);
    room.join(new Member(), 'b');
    room.leave(2);
    room.leave(1);
    clock.advance(TICK_MS);
    expect(sim.records.at(-1)).toEqual({ tick: 2, leaves: [1], joins: [], commands: [] });
    expect(sim.records.flatMap((r) => r.joins.map((j) => j.playerId))).toEqual([1]);
  });

  it('sends frames at the snapshot rate and events every tick they happen', () => {
    const { room, clock } = makeRoom({ snapshotRateHz: 20 });
    const m = new Member();
    room.join(m, 'a');
    clock.advance(59 * TICK_MS); // ticks 0..59
    expect(m.frames.map((f) => f.tick)).toEqual([2, 5, 8, 11, 14, 17, 20, 23, 26, 29, 32, 35, 38, 41, 44, 47, 50, 53, 56, 59]);
    expect(m.frames[0].bodies.count).toBe(1);
    expect(m.events.map(([t]) => t)).toEqual([0]);
  });

  it('refuses joins beyond the client and body limits with clear codes', () => {
    const full = makeRoom({ maxClients: 1 }).room;
    full.join(new Member(), 'a');
    expect(() => full.join(new Member(), 'b')).toThrow(RoomError);
    try {
      full.join(new Member(), 'b');
    } catch (e) {
      expect((e as RoomError).code).toBe('room-full');
    }
    const tight = makeRoom({ maxBodies: 1 }).room;
    tight.join(new Member(), 'a');
    expect(() => tight.join(new Member(), 'b')).toThrow(/body limit/);
  });

  it("refuses a join past the scenario's player cap with a reason, and takes one again after a leave", () => {
    const { room, sim, clock } = makeRoom({ maxClients: 10, maxPlayers: 2 });
    room.join(new Member(), 'a');
    room.join(new Member(), 'b');
    let refusal: unknown;
    try {
      room.join(new Member(), 'c');
    } catch (e) {
      refusal = e;
    }
    expect(refusal).toBeInstanceOf(RoomError);
    expect((refusal as RoomError).code).toBe('room-full');
    expect((refusal as RoomError).message).toMatch(/serves at most 2 players at 60 Hz \(its per-tick character budget/);
    clock.advance(2 * TICK_MS);
    expect(sim.players.size).toBe(2);
    room.leave(1);
    expect(room.join(new Member(), 'd').playerId).toBe(3);
  });

  it('pauses while empty and resumes on a join', () => {
    const { room, sim, clock } = makeRoom();
    clock.advance(1000);
    expect(sim.tick).toBe(0);
    room.join(new Member(), 'a');
    clock.advance(10 * TICK_MS);
    expect(sim.tick).toBe(11);
    room.leave(1);
    clock.advance(1000);
    expect(sim.tick).toBe(12); // the tick that recorded the leave, then nothing
    expect(sim.records.at(-1)?.leaves).toEqual([1]);
  });

  it('removes a member whose delivery throws and keeps serving the others', () => {
    const { room, clock } = makeRoom({ snapshotRateHz: 60 });
    const bad = new Member();
    const good = new Member();
    room.join(bad, 'bad');
    room.join(good, 'good');
    bad.throwOnFrame = true;
    clock.advance(5 * TICK_MS);
    expect(room.clientCount).toBe(1);
    expect(good.frames.length).toBe(6);
    expect(bad.removedWith).toMatch(/member broke/);
  });

  it('slows down instead of spiralling when ticks take longer than a period, and reports it', async () => {
    const { room, sim, clock, metrics } = makeRoom();
    room.join(new Member(), 'a');
    // Every step costs 40 ms of (manual) time: 2.4 periods.
    const step = sim.step.bind(sim);
    sim.step = (record) => {
      clock.advance(40);
      return step(record);
    };
    clock.advance(2000);
    // Without a limit the tick clock would chase 120 ticks forever; with it, it runs what fits and gives up the rest.
    expect(sim.tick).toBeGreaterThan(40);
    expect(sim.tick).toBeLessThan(80);
    expect(room.tickClock.slowdowns).toBeGreaterThan(0);
    const skipped = await metrics.registry.getSingleMetricAsString('taos_ticks_skipped_total');
    expect(Number(/ (\d+)$/.exec(skipped)?.[1])).toBeGreaterThan(20);
  });

  it('closes with a reason when the simulation fails, telling every member', async () => {
    const { room, sim, clock } = makeRoom();
    const m = new Member();
    const reasons: string[] = [];
    room.onClose((r) => reasons.push(r));
    room.join(m, 'a');
    sim.failOnTick = 3;
    clock.advance(10 * TICK_MS);
    await Promise.resolve();
    await Promise.resolve();
    expect(room.closed).toBe(true);
    expect(m.closedWith).toMatch(/fake sim exploded/);
    expect(sim.destroyed).toBe(true);
    expect(reasons).toHaveLength(1);
    expect(() => room.join(new Member(), 'late')).toThrow(/closed/);
  });

  it('keeps a detached player in the records with the held input and no deliveries until it is reattached', () => {
    const { room, sim, clock } = makeRoom();
    const a = new Member();
    const b = new Member();
    room.join(a, 'ann');
    room.join(b, 'bob');
    room.offerInput(1, 1, { moveX: 90, moveZ: -40, yaw: 777, pitch: -300, buttons: 3 });
    clock.advance(2 * TICK_MS);
    const framesBefore = a.frames.length;
    const detachedAt = sim.tick;
    expect(room.detach(1)).toBe(true);
    expect(room.detach(1)).toBe(false);
    room.offerInput(1, 3, cmd(127)); // nobody may speak for a held player; even if something did, it is not applied
    clock.advance(4 * TICK_MS);
    const held = { moveX: 0, moveZ: 0, yaw: 777, pitch: -300, buttons: 0 };
    expect(sim.records.length).toBe(detachedAt + 4);
    for (const r of sim.records.slice(detachedAt)) expect(r.commands.find((c) => c.playerId === 1)?.input).toEqual(held);
    expect(a.frames.length).toBe(framesBefore);
    expect(room.clientCount).toBe(2);
    expect(room.heldCount).toBe(1);
    const c = new Member();
    const back = room.reattach(1, c);
    const backAt = sim.tick;
    expect(back).toEqual({ playerId: 1, joinTick: backAt, firstInputTick: backAt });
    room.offerInput(1, backAt + 1, cmd(10));
    clock.advance(2 * TICK_MS);
    expect(sim.records[backAt + 1].commands.find((x) => x.playerId === 1)?.input).toEqual(cmd(10));
    expect(c.frames.length).toBeGreaterThan(0);
    expect(sim.records.every((r) => r.leaves.length === 0 && r.joins.every((j) => j.playerId !== 1 || r.tick === 0))).toBe(true);
    expect(room.heldCount).toBe(0);
    expect(room.reattach(99, c)).toBeNull();
  });

  it('holds each tick\'s events and frame until its recorder releases the tick, then sends them in tick order', () => {
    const held: Array<[number, () => void]> = [];
    const recorder = { append: () => {}, afterStep: () => {}, close: async () => {}, release: (tick: number, send: () => void) => held.push([tick, send]) };
    const { room, clock } = makeRoom({ snapshotRateHz: 60, recorder });
    const m = new Member();
    room.join(m, 'a');
    clock.advance(2 * TICK_MS); // ticks 0..2
    expect(held.map(([t]) => t)).toEqual([0, 1, 2]);
    expect(m.events).toEqual([]);
    expect(m.frames).toEqual([]);
    held.splice(0, 2).forEach(([, send]) => send());
    expect(m.events.map(([t]) => t)).toEqual([0]);
    expect(m.frames.map((f) => f.tick)).toEqual([0, 1]);
    expect(m.frames[0].bodies.count).toBe(1);
  });

  it('keeps the descriptors of a held frame\'s bodies from its own tick, so a body gone before the release still travels with it', () => {
    const held: Array<[number, () => void]> = [];
    const recorder = { append: () => {}, afterStep: () => {}, close: async () => {}, release: (tick: number, send: () => void) => held.push([tick, send]) };
    const { room, sim, clock } = makeRoom({ snapshotRateHz: 60, recorder });
    const describe = (id: number): BodyDescriptor => ({ id, shape: { kind: 'sphere', radius: 0.5 }, color: [1, 1, 1], motion: 'dynamic', hidden: false, position: { x: 0, y: 0, z: 0 }, rotation: { x: 0, y: 0, z: 0, w: 1 } });
    sim.bodyDescriptor = (id: number) => (sim.players.has(id) ? describe(id) : undefined);
    const watcher = new Member();
    room.join(watcher, 'w');
    const leaver = new Member();
    clock.advance(TICK_MS);
    const { playerId } = room.join(leaver, 'l')!;
    clock.advance(TICK_MS); // the leaver's body is in this tick's frame
    const frameTick = sim.tick - 1;
    room.leave(playerId);
    clock.advance(2 * TICK_MS); // ...and gone from the simulation before that frame is released
    expect(sim.players.has(playerId)).toBe(false);
    const [, send] = held.find(([t]) => t === frameTick)!;
    send();
    const frame = watcher.frames.find((f) => f.tick === frameTick)!;
    expect(Array.from(frame.bodies.ids.subarray(0, frame.bodies.count))).toContain(playerId);
    expect(frame.descriptors?.get(playerId)).toEqual(describe(playerId));
  });
});
