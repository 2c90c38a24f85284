// Wire constants both ends import: the protocol version, opcodes by direction, error codes and bye reasons.
// Every frame is a msgpack array whose first element is one of these opcodes (see docs/protocol.md).

/**
 * Bumped on any incompatible change to a message or the snapshot bit layout; hello and welcome must agree.
 * 2: hello's optional options map (seat and resume tokens); the welcome's resume fields; seat/resume codes.
 * 3: predict mode: the welcome's netMode, checkpoint and record messages, resync and netMode requests.
 * 4: the game API: game input values in input commands, the welcome's game schema, game state in snapshots, game
 *    messages (docs/protocol.md, docs/game-api.md).
 * 5: the pong's room pace (roomTicksPerSecond, roomSlow).
 * 6: the bye reason `room-moved` (and error code) with the hosting server's URL as the bye's fourth element.
 * 7: an input message's optional fourth element, a snapshot ack (one message fewer per snapshot).
 * 8: predict mode for the game API: record bits carry game input values and game messages, checkpoint input rows
 *    an optional eighth element (the player's game input values).
 * 9: the welcome's inputDelayTicks (predict mode's input delay the room announces).
 * 10: range-coded snapshots (16-bit delta ticks, "nothing changed" snapshots of a few bytes); a snapshot without
 *    descriptors or game state is framed as its opcode byte followed by the snapshot bytes, not as msgpack.
 */
export const PROTOCOL_VERSION = 10;

/** Opcodes of messages a client sends to the server (1–15). */
export const ClientOpcode = {
  Hello: 1,
  Input: 2,
  SnapshotAck: 3,
  Ping: 4,
  Bye: 5,
  Resync: 6,
  NetMode: 7,
  /** A game message (ScenarioDefinition.messages): protocol 4. */
  GameMessage: 8,
} as const;
export type ClientOpcode = (typeof ClientOpcode)[keyof typeof ClientOpcode];

/** Opcodes of messages the server sends to a client (16–31). */
export const ServerOpcode = {
  Welcome: 16,
  Pong: 17,
  Snapshot: 18,
  Events: 19,
  Error: 20,
  Bye: 21,
  Checkpoint: 22,
  Record: 23,
} as const;
export type ServerOpcode = (typeof ServerOpcode)[keyof typeof ServerOpcode];

/** Machine-readable codes of error messages (and of validation failures on the server). */
export const ErrorCode = {
  /** Not a msgpack value, or trailing bytes after it. */
  Malformed: 'malformed',
  /** Larger than the protocol's frame limit. */
  Oversize: 'oversize',
  /** A msgpack value that is not a known message (opcode, arity, field types). */
  BadMessage: 'bad-message',
  /** An input command failed `validateInputCommand`, or an input batch is out of range. */
  BadInput: 'bad-input',
  /** A message that is valid but not allowed now (input before hello, a second hello, …). */
  UnexpectedMessage: 'unexpected-message',
  /** hello.version differs from PROTOCOL_VERSION. */
  VersionMismatch: 'version-mismatch',
  RoomNotFound: 'room-not-found',
  RoomFull: 'room-full',
  ServerFull: 'server-full',
  /** Too many messages or inputs per second. */
  RateLimited: 'rate-limited',
  /** The server admits only players with a seat token (`--require-seat`) and the hello carried none. */
  SeatRequired: 'seat-required',
  /** The hello's seat token is forged, expired, already used or for another room. */
  SeatRefused: 'seat-refused',
  /** The hello's resume token is unknown, already used or past its grace window: the client joins as a new player. */
  ResumeRefused: 'resume-refused',
  /** The room is hosted by another server of the fleet; the bye that follows carries its URL. */
  RoomMoved: 'room-moved',
  Internal: 'internal',
} as const;
export type ErrorCode = (typeof ErrorCode)[keyof typeof ErrorCode];

/** Why the server ends a session; a client reconnects only after the reasons in RECONNECTABLE_BYE_REASONS. */
export const ByeReason = {
  ServerShutdown: 'server-shutdown',
  RoomClosed: 'room-closed',
  Kicked: 'kicked',
  TooManyErrors: 'too-many-errors',
  Flood: 'flood',
  Timeout: 'timeout',
  VersionMismatch: 'version-mismatch',
  RoomFull: 'room-full',
  ServerFull: 'server-full',
  RoomNotFound: 'room-not-found',
  /** No valid seat token (the error before it says which: `seat-required` or `seat-refused`). */
  SeatRefused: 'seat-refused',
  /** Another connection resumed this player with its resume token; this one is no longer in the room. */
  Replaced: 'replaced',
  /** The room is hosted by another server of the fleet: the bye's `url` says where (the client connects there). */
  RoomMoved: 'room-moved',
  ClientBye: 'client-bye',
} as const;
export type ByeReason = (typeof ByeReason)[keyof typeof ByeReason];

/**
 * Bye reasons after which reconnecting at once can succeed: only a timeout (the link went quiet). A shutdown, a full
 * room or server and every refusal end the client with the server's reason; the application decides when to try again.
 */
export const RECONNECTABLE_BYE_REASONS: ReadonlySet<string> = new Set<string>([ByeReason.Timeout]);
