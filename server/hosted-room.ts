// What the main thread needs of a room wherever it runs: on this thread (Room) or in a room worker (RemoteRoom). The
// session enters a room through a MemberSink (where the room's bytes for that member go) and gets a Seat back.
import type { InputCommand } from '../shared/sim/input.ts';
import type { NetMode, WelcomeMessage } from '../shared/protocol/index.ts';
import type { OfferResult } from './input-buffer.ts';
import type { RoomInfo } from './room.ts';

/** What a room's deliveries are to the member's link: reliable events or welcome data, or a droppable snapshot. */
export const DeliveryKind = { Reliable: 0, Snapshot: 1 } as const;
export type DeliveryKind = (typeof DeliveryKind)[keyof typeof DeliveryKind];

/** Where a room sends one member's bytes (the client session implements it on the main thread). */
export interface MemberSink {
  /** One framed server message for the member's socket; a snapshot comes with its tick where the caller knows it. */
  deliver(bytes: Uint8Array, kind: DeliveryKind, snapshotTick?: number): void;
  /** A snapshot was not sent because the member's socket is backed up. */
  snapshotSkipped(): void;
  /** Whether the member's socket is backed up (snapshots are skipped while it is). */
  backedUp(): boolean;
  /** True (and the member is disconnected) when reliable messages can no longer be queued for it. */
  tooFarBehind(): boolean;
  /** The room closed; the member is no longer in it. */
  roomClosed(reason: string): void;
  /** The room removed this member (its delivery failed). */
  removed(reason: string): void;
}

/** How a member enters: as a new player, or taking back a player it holds a resume claim for. */
export type RoomEntry = { name: string } | { resumePlayerId: number };

/** Commands of an input message that came too late for their tick, or too far ahead of the room. */
export interface OfferTally {
  inputsLate: number;
  inputsTooFar: number;
}

/** A member's place in a room once entered. */
export interface Seat {
  readonly playerId: number;
  /** The welcome to send (its resume token and grace are filled in by the session). */
  readonly welcome: WelcomeMessage;
  /** Offers a validated command stamped for `tick`; null when the result is not known here (room in a worker). */
  offerInput(tick: number, command: InputCommand): OfferResult | null;
  /**
   * Offers a message's validated commands, stamped `firstTick`, `firstTick + 1`, …, and adds the late and too-far ones
   * to `tally` (where known: a room in a worker tallies nothing here).
   */
  offerInputs(firstTick: number, commands: readonly InputCommand[], tally: OfferTally): void;
  /**
   * Queues a game message (its kind already checked against the welcome's schema) for the room's next tick; returns
   * why the room refused it, or null (accepted, or not known here: a room in a worker drops what it refuses).
   */
  offerMessage(name: string, payload: readonly number[], tick?: number): string | null;
  /** The client acknowledged the snapshot of `tick`. */
  acknowledge(tick: number): void;
  /**
   * Serves the member in `mode` from the next tick on (predict only in a predict-mode room: the welcome says). Asking
   * for predict again is a resync: a fresh checkpoint goes out before the next record.
   */
  setNetMode(mode: NetMode): void;
  /** The room's tick counter as last seen on this thread. */
  serverTick(): number;
  /** Ticks on which this player's input had not arrived and the last one was repeated. */
  missedInputTicks(): number;
  /** The room's ticks per second over the last second and whether it runs slowed (for the player's HUD). */
  pace(): { ticksPerSecond: number; slow: boolean };
}

/** A room as the room manager, the sessions, the HTTP API and the resume tokens use it. */
export interface HostedRoom {
  readonly id: string;
  readonly scenarioName: string;
  readonly params: Readonly<Record<string, number>>;
  readonly closed: boolean;
  /** The input log the room records into, when its host says (a room worker's); resume keys are kept beside it. */
  readonly recordingPath?: string | null;
  /** Players in the room, counting those held for a reconnect. */
  readonly clientCount: number;
  info(): RoomInfo;
  /** The room's WASM heap, or null when closed or unknown. */
  heapUsage(): { usedBytes: number; freeBytes: number } | null;
  hasPlayer(playerId: number): boolean;
  /** The player's link dropped: its character stays, held (see Room.detach). */
  detach(playerId: number): boolean;
  leave(playerId: number): void;
  /** Seats a member; rejects with a RoomError when refused. */
  enter(sink: MemberSink, entry: RoomEntry): Promise<Seat>;
  onClose(fn: (reason: string) => void): () => void;
  onEmptyChange(fn: (empty: boolean) => void): () => void;
  start(): void;
  close(reason: string): Promise<void>;
}
