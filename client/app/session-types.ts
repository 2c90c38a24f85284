// What the page needs from a network session, independent of how the client library spells it: the welcome,
// interpolated views per frame, descriptors and events as they arrive, stats, input, and how the session ended.
import type { SnapshotView } from '../../shared/protocol/snapshot-frame.ts';
import type { ScenarioInfo } from '../../shared/protocol/server-messages.ts';
import type { InputCommand } from '../../shared/sim/input.ts';
import type { BodyDescriptor, SimEvent } from '../../shared/sim/types.ts';
import type { PredictionStats } from '../../sdk/index.ts';

/** The welcome, as the page uses it. */
export interface SessionWelcome {
  playerId: number;
  roomId: string;
  tick: number;
  tickRateHz: number;
  snapshotRateHz: number;
  scenario: ScenarioInfo;
  staticBodies: BodyDescriptor[];
  dynamicBodies: BodyDescriptor[];
  /** How the room serves this client: snapshots, or its inputs for the page's own simulation (predicted play). */
  netMode: 'snapshot' | 'predict';
}

/** The predicted world for one frame: the own simulation's present tick, smoothed. */
export interface PredictedSessionFrame {
  /** Ticks simulated locally (the own newest input is in it). */
  tick: number;
  view: SnapshotView;
}

/** The interpolated world for one frame. */
export interface SessionFrame {
  view: SnapshotView | null;
  /** The (fractional) tick being shown. */
  renderTick: number;
  /** Snapshots buffered ahead of the render time. */
  bufferDepth: number;
  /** How far behind the estimated server time the render time is (ms). */
  delayMs: number;
}

/** Callbacks a session calls as things arrive. */
export interface SessionHandlers {
  onWelcome(welcome: SessionWelcome): void;
  /** A snapshot was decoded (its tick, its size on the wire, descriptors of spawned bodies it carried). */
  onSnapshot(tick: number, sizeBytes: number, descriptors: readonly BodyDescriptor[]): void;
  onEvents(events: readonly SimEvent[]): void;
  /** The connection dropped and the library is trying again (attempt counts from 1). */
  /** The link dropped and the client library is retrying; `serverRestarting`: the server itself went away. */
  onReconnecting(attempt: number, reason: string, serverRestarting: boolean): void;
  /** The session is over for good (server bye, refused, unreachable, or our own close). */
  onClosed(reason: string, detail: string): void;
  /** Something worth telling the user that does not end the session (a refused message, a bad snapshot). */
  onNotice(line: string): void;
}

/** A live connection to one room. */
export interface NetSession {
  /** Latest server tick heard of. */
  readonly serverTick: number;
  /** Round-trip time (ms), null before the first pong. */
  readonly rttMs: number | null;
  /** How many ticks ahead of the server our inputs are stamped (null before the welcome). */
  readonly inputLeadTicks: number | null;
  /** The newest tick an own command was fixed and sent for (−1 before any): a new command goes into later ticks. */
  readonly newestInputTick: number;
  /** The room's ticks per second and whether the server says it runs slowed (null before the first pong). */
  readonly roomPace: { ticksPerSecond: number; slow: boolean } | null;
  /** The interpolated world at `nowMs` (performance.now() clock). */
  frame(nowMs: number): SessionFrame;
  /** The predicted world while the page runs the room's simulation itself (predict mode), else null. */
  predicted(): PredictedSessionFrame | null;
  /** A body's descriptor as the session knows it (while predicting: from the own simulation). */
  descriptor(id: number): BodyDescriptor | undefined;
  /** Predicted play's numbers (mode, input delay, rollback depth, re-sim ms, corrections, desyncs); null: snapshots. */
  readonly prediction: PredictionStats | null;
  /** Bytes per second received, as kilobits (every message, not only snapshots). */
  readonly kbpsIn: number;
  /** The command to send for the coming ticks (the library sends at 60 Hz). */
  setInput(cmd: InputCommand): void;
  close(): void;
}
