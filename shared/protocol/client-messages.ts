// Messages a client sends to the server, as typed objects (the wire form of each is in codec.ts and
// docs/protocol.md). The server only ever sees these after validation.ts has checked them.
import type { InputCommand } from '../sim/input.ts';
import type { NetModeMessage, ResyncMessage } from './predict-messages.ts';

/**
 * First message on a connection: protocol version, display name, the room to join (null: the default room), and
 * optionally a seat token (servers that admit only reserved seats) and a resume token (take back a dropped player).
 */
export interface HelloMessage {
  type: 'hello';
  version: number;
  /** 1–32 characters after trimming, no control characters. */
  name: string;
  /** Room id (letters, digits, '-', '_'), or null for the default room (or the room the token names). */
  room: string | null;
  /** A seat token from `POST /api/rooms/:id/seats`. */
  seatToken?: string;
  /** The resume token of an earlier welcome: the server hands that player back instead of adding a new one. */
  resumeToken?: string;
}

/** Commands for consecutive ticks firstTick, firstTick+1, …; the newest is last, the earlier ones are repeats. */
export interface InputMessage {
  type: 'input';
  firstTick: number;
  /** 1..MAX_INPUT_COMMANDS_PER_MESSAGE commands, each passed through validateInputCommand. */
  commands: InputCommand[];
  /**
   * A snapshot ack riding along (protocol 7): the client decoded the snapshot of this tick, exactly as an `ack`
   * message says; absent when there is nothing new to ack.
   */
  ackTick?: number;
}

/** The client decoded the snapshot of this tick: the server may use it as a delta baseline. */
export interface SnapshotAckMessage {
  type: 'ack';
  tick: number;
}

/** Clock-sync probe; the server answers at once with a pong echoing clientTimeMs. */
export interface PingMessage {
  type: 'ping';
  /** The client's own monotonic clock (ms), opaque to the server. */
  clientTimeMs: number;
}

/** The client is leaving on purpose. */
export interface ClientByeMessage {
  type: 'bye';
}

/** A game message: a kind the scenario declares and its payload in the kind's field order (stamped by the server). */
export interface GameMessageMessage {
  type: 'game';
  name: string;
  /** At most 8 integers within ±1 000 000. */
  payload: number[];
  /**
   * The tick a predicting client's own simulation applies it on: the server applies it then, or on its next tick when
   * that one has passed (absent: its next tick). Beyond the input lead limit it counts as that limit.
   */
  tick?: number;
}

/** Every client→server message. */
export type ClientMessage = HelloMessage | InputMessage | SnapshotAckMessage | PingMessage | ClientByeMessage | ResyncMessage | NetModeMessage | GameMessageMessage;
