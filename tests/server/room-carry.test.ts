// Tests for Room.handOff() and a Room built from its carry (server/room-carry.ts): a room moved between two ticks
// steps exactly the records a room that never moved steps — inputs stamped ahead, a held player, a join and a leave
// still waiting for their record, its game messages — and its members hear nothing of the move.
import { describe, expect, it } from 'vitest';
import { silentLogger } from '../../server/logger.ts';
import { createMetrics } from '../../server/metrics.ts';
import { Room, type BodyStates, type RoomMember, type RoomOptions, type RoomSimulation, type WorldFrame } from '../../server/room.ts';
import { ManualClock } from '../../shared/clock.ts';
import type { GameMessageKind } from '../../shared/sim/game-messages.ts';
import { NEUTRAL_INPUT, type InputCommand } from '../../shared/sim/input.ts';
import type { BodyDescriptor, CharacterState, SimEvent, TickInputRecord } from '../../shared/sim/types.ts';
import { TICK_MS } from '../../shared/tick-rate.ts';

// A stand-in simulation whose checkpoint is its tick and players; it remembers the records it stepped.
class FakeSim implements RoomSimulation {
  tick = 0;
  players = new Set<number>();
  readonly records: TickInputRecord[] = [];
  destroyed = false;
  readonly gameMessageKinds: GameMessageKind[] = [{ name: 'ping', fields: [] } as unknown as GameMessageKind];

  step(record: TickInputRecord): SimEvent[] {
    if (record.tick !== this.tick) throw new Error(`fake sim: got tick ${record.tick}, at ${this.tick}`);
    this.records.push(structuredClone(record));
    for (const id of record.leaves) this.players.delete(id);
    for (const j of record.joins) this.players.add(j.playerId);
    this.tick++;
    return [];
  }
  stateHash(): string {
    return `${this.tick}:${[...this.players].join(',')}`;
  }
  saveCheckpointBytes(): Uint8Array {
    return new TextEncoder().encode(JSON.stringify({ tick: this.tick, players: [...this.players] }));
  }
  static restored(bytes: Uint8Array): FakeSim {
    const sim = new FakeSim();
    const { tick, players } = JSON.parse(new TextDecoder().decode(bytes)) as { tick: number; players: number[] };
    sim.tick = tick;
    sim.players = new Set(players);
    return sim;
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
  frames = 0;
  closedWith: string | null = null;
  deliverEvents(): void {}
  deliverFrame(_frame: WorldFrame): void {
    this.frames++;
  }
  roomClosed(reason: string): void {
    this.closedWith = reason;
  }
  removed(): void {}
}

const cmd = (moveX: number): InputCommand => ({ ...NEUTRAL_INPUT, moveX });

function options(clock: ManualClock, over: Partial<RoomOptions> = {}): RoomOptions {
  return { id: 'r', scenarioName: 'fake', params: {}, seed: 1, clock, metrics: createMetrics({ processMetrics: false }), logger: silentLogger(), snapshotRateHz: 30, maxClients: 8, maxBodies: 100, ...over };
}

// The same session on any room: three players, inputs stamped ahead, one held, one leaving, one joining late.
function playUntilMove(room: Room, clock: ManualClock, members: Member[]): void {
  for (const [i, name] of ['ann', 'bob', 'cy'].entries()) room.join(members[i], name);
  room.offerInput(1, 1, cmd(10));
  room.offerInput(2, 2, cmd(20));
  clock.advance(3 * TICK_MS);
  room.offerInput(1, 5, cmd(50)); // ahead of the move, applied after it
  room.offerInput(1, 7, cmd(70));
  room.detach(2); // held across the move
  room.leave(3); // its leave waits for the next record
  room.join(members[3], 'dee'); // so does this join
  expect(room.offerMessage(1, 'ping', [])).toBeNull();
}

// A started room ticks at once: the moved room's first tick after the move runs at start(), not a period later.
function playAfterMove(room: Room, clock: ManualClock, periods: number): void {
  room.offerInput(4, 6, cmd(-40));
  clock.advance(periods * TICK_MS);
}

describe('Room hand-off', () => {
  it('steps the same records after a move as a room that never moved, and its members hear nothing of it', async () => {
    const refClock = new ManualClock();
    const refSim = new FakeSim();
    const ref = new Room(refSim, options(refClock));
    ref.start();
    playUntilMove(ref, refClock, [new Member(), new Member(), new Member(), new Member()]);
    playAfterMove(ref, refClock, 5);

    const clock = new ManualClock();
    const oldSim = new FakeSim();
    const old = new Room(oldSim, options(clock));
    old.start();
    const members = [new Member(), new Member(), new Member(), new Member()];
    playUntilMove(old, clock, members);
    const closed: string[] = [];
    old.onClose((reason) => closed.push(reason));
    const carry = await old.handOff();
    expect(carry).toMatchObject({ tick: 4, hash: oldSim.stateHash(), pendingLeaves: [3], nextPlayerId: 5, log: null, predictInputs: null });
    expect(carry.players.map((p) => [p.playerId, p.held, p.inWorld])).toEqual([
      [1, false, true],
      [2, true, true],
      [4, false, false],
    ]);
    expect(oldSim.destroyed).toBe(true);
    expect(old.closed).toBe(true);
    expect(closed).toEqual([]);
    expect(members.map((m) => m.closedWith)).toEqual([null, null, null, null]);

    const sim = FakeSim.restored(carry.checkpoint);
    const moved = new Room(sim, options(clock, { carried: carry }));
    expect(moved.reattach(1, members[0])).toMatchObject({ playerId: 1, firstInputTick: 4 });
    expect(moved.reattach(4, members[3])).not.toBeNull();
    moved.start();
    expect(moved.clientCount).toBe(3);
    expect(moved.heldCount).toBe(1);
    playAfterMove(moved, clock, 4);
    expect([...oldSim.records, ...sim.records]).toEqual(refSim.records);
    expect(sim.stateHash()).toBe(refSim.stateHash());
    expect(sim.records[0]).toMatchObject({ tick: 4, leaves: [3], joins: [{ playerId: 4, name: 'dee' }], messages: [{ playerId: 1, name: 'ping' }] });
    expect(sim.records[1]).toMatchObject({ tick: 5, commands: [{ playerId: 1, input: cmd(50) }, { playerId: 2, input: cmd(0) }, { playerId: 4, input: NEUTRAL_INPUT }] }); // 2 is held: it stands still
    expect(members[0].frames).toBeGreaterThan(0);
    // New players after the move get ids after every id the room ever gave.
    expect(moved.join(new Member(), 'eve').playerId).toBe(5);
  });

  it('refuses to hand off a closed room', async () => {
    const clock = new ManualClock();
    const room = new Room(new FakeSim(), options(clock));
    await room.close('done');
    await expect(room.handOff()).rejects.toThrow(/closed/);
  });
});
