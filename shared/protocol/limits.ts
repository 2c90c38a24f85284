// Size and range limits of the protocol: what validation enforces on every client message, and the defaults the
// snapshot history and input redundancy use. The server sets `ws` maxPayload from MAX_CLIENT_MESSAGE_BYTES.

/** Largest client→server frame accepted (bytes); anything larger is rejected before decoding. */
export const MAX_CLIENT_MESSAGE_BYTES = 1024;
/** Most nested containers in a client frame (an input message nests 3: message, command list, command). */
export const MAX_CLIENT_FRAME_DEPTH = 8;
/** Longest player name (UTF-16 code units, after trimming). */
export const MAX_NAME_LENGTH = 32;
/** Longest room id. */
export const MAX_ROOM_ID_LENGTH = 64;
/** Room ids: letters, digits, '-' and '_' only. */
export const ROOM_ID_PATTERN = /^[A-Za-z0-9_-]{1,64}$/;
/** Most commands in one input message (the newest plus repeats of the previous ones). */
export const MAX_INPUT_COMMANDS_PER_MESSAGE = 16;
/** Most ticks of input delay a room may announce (predict mode: own commands apply this many ticks later). */
export const MAX_INPUT_DELAY_TICKS = 15;
/** Default number of commands per input message: the new one plus three repeats. */
export const DEFAULT_INPUT_REDUNDANCY = 4;
/** Ticks are unsigned 32-bit on the wire (2^32 ticks at 60 Hz is 2.2 years). */
export const MAX_TICK = 0xffff_ffff;
/** Largest |clientTimeMs| accepted in a ping (a millisecond clock far beyond any session). */
export const MAX_CLIENT_TIME_MS = 1e15;
/** Snapshots the server remembers per client as possible baselines (and the client keeps decoded). */
export const SNAPSHOT_HISTORY_SIZE = 64;
/** Longest seat or resume token in a hello. */
export const MAX_TOKEN_LENGTH = 256;
/** Seat and resume tokens: URL-safe base64 characters and dots only. */
export const TOKEN_PATTERN = /^[A-Za-z0-9_.-]{1,256}$/;
