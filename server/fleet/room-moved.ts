// The refusal "this room is hosted by another server of the fleet": a RoomError that carries the host's URLs, so a
// WebSocket hello is answered with a `room-moved` bye naming the host and an HTTP request with a JSON answer.
import { ErrorCode } from '../../shared/protocol/opcodes.ts';
import { RoomError } from '../room.ts';

/** Where a fleet member can be reached. */
export interface MemberAddress {
  /** The member's id in the directory. */
  id: string;
  /** Its public HTTP(S) base URL, e.g. `http://10.0.0.7:8080/`. */
  url: string;
  /** Its WebSocket URL (ws:// or wss://). */
  wsUrl: string;
}

/** A room that another fleet member hosts (or claimed first). */
export class RoomMovedError extends RoomError {
  readonly roomId: string;
  readonly host: MemberAddress;
  constructor(roomId: string, host: MemberAddress, message?: string) {
    super(ErrorCode.RoomMoved, message ?? `room ${JSON.stringify(roomId)} is hosted by another server of the fleet (${host.url}): connect there`);
    this.name = 'RoomMovedError';
    this.roomId = roomId;
    this.host = host;
  }
}

/** The WebSocket URL of an HTTP(S) base URL (http → ws, https → wss; path kept). */
export function webSocketUrl(httpUrl: string): string {
  const u = new URL(httpUrl);
  if (u.protocol === 'http:') u.protocol = 'ws:';
  else if (u.protocol === 'https:') u.protocol = 'wss:';
  else throw new Error(`a public URL must be http:// or https://, got ${JSON.stringify(httpUrl)}`);
  return u.href;
}
