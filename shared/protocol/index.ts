// Public surface of the wire protocol: the server and the client library import from here (pure, isomorphic).
export { BitReader, BitWriter, bestExpGolombOrder, bitsFor, expGolombBits, unzigzag, zigzag } from './bit-stream.ts';
export type { ClientByeMessage, ClientMessage, GameMessageMessage, HelloMessage, InputMessage, PingMessage, SnapshotAckMessage } from './client-messages.ts';
export { decodeFrame, encodeClientMessage, encodeServerMessage, FrameError, MAX_SERVER_FRAME_DEPTH, packValue, toBytes, unpackFrame, type FrameDecode } from './codec.ts';
export { FrameLease, frameIsLive, QuantizedFramePool, type PooledArrays } from './frame-pool.ts';
export { packDescriptors, parseShape, unpackDescriptors, type PackedDescriptors } from './descriptor-codec.ts';
export * from './limits.ts';
export { ByeReason, ClientOpcode, ErrorCode, PROTOCOL_VERSION, RECONNECTABLE_BYE_REASONS, ServerOpcode } from './opcodes.ts';
export {
  createSnapshotFormat,
  DEFAULT_MAX_POSITION_STEP_METRES,
  DEFAULT_ROTATION_BITS,
  dequantizeAxis,
  dequantizeRotation,
  quantizeAxis,
  quantizeRotation,
  snapshotFormatFromSpec,
  snapshotFormatSpec,
  type Bounds,
  type SnapshotFormat,
  type SnapshotFormatSpec,
} from './quantization.ts';
export { checkGameStateValues, packGameSchema, unpackGameSchema, type GameSchemaInfo, type StateFieldInfo } from './game-schema-codec.ts';
export { decodeServerMessage, type ServerDecodeResult } from './server-message-decoder.ts';
export type { ErrorMessage, EventsMessage, PongMessage, ScenarioInfo, ServerByeMessage, ServerMessage, SnapshotMessage, WelcomeMessage } from './server-messages.ts';
export { decodeSnapshot, encodeSnapshot, readSnapshotHeader, type SnapshotHeader } from './snapshot-codec.ts';
export {
  BODY_Q_STRIDE,
  BodyQ,
  CHARACTER_Q_STRIDE,
  CharacterQ,
  dequantizeFrame,
  emptyFrame,
  framesEqual,
  quantizeFrame,
  type BodyStatesRead,
  type QuantizedFrame,
  type QuantizeFrameOptions,
  type SnapshotView,
} from './snapshot-frame.ts';
export { SharedFrameWork, SnapshotDecoder, SnapshotEncoder, TickHistory, type AckOutcome, type DecodedSnapshot, type EncodedSnapshot, type SnapshotEncoderStats } from './snapshot-stream.ts';
export { checkPlayerName, checkRoomId, decodeClientMessage, type ClientDecodeResult } from './validation.ts';
export { carriesHash, HASH_INTERVAL_TICKS, isNetMode, MAX_CHECKPOINT_BYTES, NetMode, type CheckpointMessage, type NetModeMessage, type RecordMessage, type ResyncMessage } from './predict-messages.ts';
export { MAX_RECORD_MEMBERSHIP_CHANGES, RecordDeltaCoder, type PlayerInputState } from './record-delta.ts';
