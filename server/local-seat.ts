// Entering a room that runs on this thread: the member's DeliveringMember joins (or takes back a held player), the
// welcome is built from the live room, and the seat feeds inputs and acks straight in.
import { ErrorCode } from '../shared/protocol/opcodes.ts';
import type { MemberSink, RoomEntry, Seat } from './hosted-room.ts';
import { DeliveringMember } from './member-delivery.ts';
import type { ServerMetrics } from './metrics.ts';
import { RoomError, type Room } from './room.ts';
import { buildWelcome } from './welcome.ts';

/** Seats `sink` in `room` (throws RoomError when refused). Used by Room.enter and by the room worker. */
export function enterRoom(room: Room, sink: MemberSink, entry: RoomEntry, metrics: ServerMetrics): Seat & { member: DeliveringMember } {
  const member = new DeliveringMember(sink, room.snapshots, metrics, room.predictFeed);
  let playerId: number;
  if ('resumePlayerId' in entry) {
    if (room.reattach(entry.resumePlayerId, member) === null) throw new RoomError(ErrorCode.RoomNotFound, `player ${entry.resumePlayerId} is no longer in room ${room.id}`);
    playerId = entry.resumePlayerId;
  } else {
    playerId = room.join(member, entry.name).playerId;
  }
  const built = buildWelcome(room, playerId, { token: null, graceMs: 0, resumed: 'resumePlayerId' in entry });
  member.encoder = built.encoder;
  return { ...seatOf(room, playerId, member), welcome: built.message };
}

/** The seat of a player whose member is already in `room` (a room moved in from another thread: no new welcome). */
export function seatOf(room: Room, playerId: number, member: DeliveringMember): Omit<Seat, 'welcome'> & { member: DeliveringMember } {
  return {
    member,
    playerId,
    offerInput: (tick, command) => room.offerInput(playerId, tick, command),
    offerInputs: (firstTick, commands, tally) => room.offerInputs(playerId, firstTick, commands, tally),
    offerMessage: (name, payload, tick) => room.offerMessage(playerId, name, payload, tick),
    // The member's current encoder: a fall back from predict mode starts a new one.
    acknowledge: (tick) => member.encoder?.acknowledge(tick),
    setNetMode: (mode) => void member.setNetMode(mode),
    serverTick: () => room.sim.tick,
    missedInputTicks: () => room.missedInputTicks(playerId),
    pace: () => room.pace(),
  };
}
