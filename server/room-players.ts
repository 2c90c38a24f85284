// A room's players: each one's member (null while held for a reconnect), input buffer and whether its join is in a
// record yet, the leaves waiting for the next record, and the joins, leaves and commands of each tick's record.
import type { InputCommand } from '../shared/sim/input.ts';
import type { TickInputRecord } from '../shared/sim/types.ts';
import { InputBuffer } from './input-buffer.ts';
import type { RoomMember } from './room-contracts.ts';
import type { CarriedPlayer } from './room-carry.ts';

/** One player of a room. */
export interface RoomPlayer {
  playerId: number;
  name: string;
  /** Null while the player's link is down and the room holds its character for a reconnect. */
  member: RoomMember | null;
  inputs: InputBuffer;
  /** True once the join has gone into a record. */
  inWorld: boolean;
}

/** A seat whose member is connected. */
export type ConnectedPlayer = RoomPlayer & { member: RoomMember };

/** The players of one room, by player id. */
export class RoomPlayers {
  private readonly byId = new Map<number, RoomPlayer>();
  private pendingLeaves: number[] = [];
  private nextPlayerId = 1;
  private readonly maxInputLeadTicks: number;

  constructor(maxInputLeadTicks: number) {
    this.maxInputLeadTicks = maxInputLeadTicks;
  }

  get size(): number {
    return this.byId.size;
  }

  get(playerId: number): RoomPlayer | undefined {
    return this.byId.get(playerId);
  }

  has(playerId: number): boolean {
    return this.byId.has(playerId);
  }

  /** Player ids in the order they were seated. */
  ids(): number[] {
    return [...this.byId.keys()];
  }

  /** Players held for a reconnect. */
  get heldCount(): number {
    let n = 0;
    for (const p of this.byId.values()) if (p.member === null) n++;
    return n;
  }

  /** Players whose join has not gone into a record yet (each will add a character). */
  get pendingJoinCount(): number {
    let n = 0;
    for (const p of this.byId.values()) if (!p.inWorld) n++;
    return n;
  }

  /** Whether a leave waits for the next record. */
  get hasPendingLeaves(): boolean {
    return this.pendingLeaves.length > 0;
  }

  /** Seats a new player whose inputs apply from `firstInputTick`; returns its id. */
  add(name: string, member: RoomMember, firstInputTick: number): number {
    const playerId = this.nextPlayerId++;
    this.byId.set(playerId, { playerId, name, member, inputs: new InputBuffer(firstInputTick, this.maxInputLeadTicks), inWorld: false });
    return playerId;
  }

  /** Seats a player already in the world, held, applying `held` from `tick`; later ids come after `lastPlayerId`. */
  restore(playerId: number, name: string, held: InputCommand, tick: number, lastPlayerId: number): void {
    const inputs = new InputBuffer(tick, this.maxInputLeadTicks);
    inputs.suspend(held);
    this.byId.set(playerId, { playerId, name, member: null, inputs, inWorld: true });
    this.nextPlayerId = Math.max(this.nextPlayerId, lastPlayerId + 1);
  }

  /** Unseats a player; its leave waits for the next record when its join was in one. */
  remove(playerId: number): RoomPlayer | undefined {
    const p = this.byId.get(playerId);
    if (!p) return undefined;
    this.byId.delete(playerId);
    if (p.inWorld) this.pendingLeaves.push(playerId);
    return p;
  }

  /** The leaves, joins and commands of `tick`'s record (ascending player id); `onRepeated` per repeated input. */
  takeRecord(tick: number, onRepeated: () => void): Pick<TickInputRecord, 'leaves' | 'joins' | 'commands'> {
    const leaves = this.pendingLeaves.sort((a, b) => a - b);
    this.pendingLeaves = [];
    const joins: TickInputRecord['joins'] = [];
    const commands: TickInputRecord['commands'] = [];
    for (const p of this.ascending()) {
      if (!p.inWorld) {
        joins.push({ playerId: p.playerId, name: p.name });
        continue;
      }
      const taken = p.inputs.take(tick);
      if (taken.repeated) onRepeated();
      commands.push({ playerId: p.playerId, input: taken.command });
    }
    return { leaves, joins, commands };
  }

  /** The players in ascending id: the map's own order (ids are handed out rising), sorted only when it is not. */
  private ascending(): Iterable<RoomPlayer> {
    let last = -1;
    for (const id of this.byId.keys()) {
      if (id < last) return [...this.byId.values()].sort((a, b) => a.playerId - b.playerId);
      last = id;
    }
    return this.byId.values();
  }

  /** Whether any seat with a connected member passes `test` (no list made). */
  someConnected(test: (p: ConnectedPlayer) => boolean): boolean {
    for (const p of this.byId.values()) if (p.member !== null && test(p as ConnectedPlayer)) return true;
    return false;
  }

  /** The record's joins were stepped: those players are in the world. */
  joined(joins: TickInputRecord['joins']): void {
    for (const j of joins) {
      const p = this.byId.get(j.playerId);
      if (p) p.inWorld = true;
    }
  }

  /** Seats whose member is connected, in seating order. */
  connected(): ConnectedPlayer[] {
    return [...this.byId.values()].filter((p): p is ConnectedPlayer => p.member !== null);
  }

  /** The players as a moving room carries them (room-carry.ts), with the id counter and the leaves still due. */
  carry(): { players: CarriedPlayer[]; nextPlayerId: number; pendingLeaves: number[] } {
    const players = [...this.byId.values()].map((p) => ({ playerId: p.playerId, name: p.name, inWorld: p.inWorld, held: p.member === null, inputs: p.inputs.exportState() }));
    return { players, nextPlayerId: this.nextPlayerId, pendingLeaves: [...this.pendingLeaves] };
  }

  /** Seats a moved room's players, every one held until its member reattaches. */
  adopt(c: { players: readonly CarriedPlayer[]; nextPlayerId: number; pendingLeaves: readonly number[] }): void {
    for (const p of c.players) this.byId.set(p.playerId, { playerId: p.playerId, name: p.name, member: null, inputs: InputBuffer.fromState(p.inputs), inWorld: p.inWorld });
    this.nextPlayerId = c.nextPlayerId;
    this.pendingLeaves = [...c.pendingLeaves];
  }

  /** Unseats everyone (the room closed) and returns who was seated. */
  clear(): RoomPlayer[] {
    const all = [...this.byId.values()];
    this.byId.clear();
    this.pendingLeaves = [];
    return all;
  }
}
