// Public surface of the client network library (browser and Node 24): connect(), the interpolation buffer, the
// transports and the pieces tests and tools reuse.
export type { Clock, TimerHandle } from '../shared/clock.ts';
export { connect, NetClient, type ClosedInfo, type NetClientEvents, type NetClientOptions, type NetClientState, type NetClientStats } from './client.ts';
export { RealClock } from './clock.ts';
export type { PlayerInput } from './game-input.ts';
export type { GameStateChange } from './game-state.ts';
export { ClockSync, type ClockSyncOptions, type PongSample } from './clock-sync.ts';
export { AckCarrier, InputLead, InputSender, type InputLeadOptions, type InputSenderOptions } from './input-sender.ts';
export { InterpolationBuffer, slerpInto, type InterpolatedFrame, type InterpolationMode, type InterpolationOptions, type InterpolationStats, type PushOutcome } from './interpolation.ts';
export type { LinkClosedInfo, SnapshotInfo } from './link-session.ts';
export { MemoryNetwork, type MemoryNetworkOptions, type MemoryPeer, type MemoryTransport } from './memory-transport.ts';
export { backoffDelayMs, isRetryable, reconnectPolicy, type ReconnectOptions, type ReconnectPolicy } from './reconnect-policy.ts';
export type { Transport, TransportFactory, TransportHandlers } from './transport.ts';
export { ABNORMAL_CLOSE, webSocketTransport } from './websocket-transport.ts';
export { Predictor, type AdvanceReport, type PredictorHandlers, type PredictSimulation } from './prediction/predictor.ts';
export { PredictSession, type PredictedFrame, type PredictionStats, type PredictOptions, type PredictSetup } from './prediction/predict-session.ts';
export { CorrectionSmoother, type BodyRead } from './prediction/smoothing.ts';
