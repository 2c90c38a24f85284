// One member's deliveries out of a room: the tick's events (reliable) and its snapshots, encoded by the member's own
// SnapshotEncoder from the room's shared fan-out work and handed to a MemberSink; in predict mode instead a checkpoint
// and then every tick's record. The same code runs beside a room on the main thread and inside a room worker; it
// never touches a socket.
import { NetMode, SnapshotEncoder } from '../shared/protocol/index.ts';
import type { SimEvent } from '../shared/sim/types.ts';
import { DeliveryKind, type MemberSink } from './hosted-room.ts';
import type { ServerMetrics } from './metrics.ts';
import type { PredictFeed } from './predict-feed.ts';
import type { RoomMember, WorldFrame } from './room.ts';
import type { SnapshotFanOut } from './snapshot-fan-out.ts';

/** A member's predict stream: snapshots instead, streaming records, or a checkpoint due before the next record. */
export type PredictState = 'off' | 'on' | 'pending';

/** Room-side half of a member: encodes for it and hands the bytes to its sink. */
export class DeliveringMember implements RoomMember {
  /** Set once the welcome is built (it counts the welcome's bodies as known); nothing is sent before. */
  encoder: SnapshotEncoder | null = null;
  private readonly sink: MemberSink;
  private readonly fanOut: SnapshotFanOut;
  private readonly metrics: ServerMetrics;
  private readonly feed: PredictFeed | null;
  /** How the member is served: snapshots (every member starts so) or, once it asks, predict mode. */
  private delivery: NetMode = NetMode.Snapshot;
  /** A checkpoint waiting for the release of its tick's record: it goes out right before that record. */
  private checkpoint: { tick: number; message: Uint8Array } | null = null;
  /** The game state version this member was last sent (−1: none yet). */
  private heldStateVersion = -1;

  constructor(sink: MemberSink, fanOut: SnapshotFanOut, metrics: ServerMetrics, feed: PredictFeed | null = null) {
    this.sink = sink;
    this.fanOut = fanOut;
    this.metrics = metrics;
    this.feed = feed;
  }

  /** The mode this member is served in. */
  get netMode(): NetMode {
    return this.delivery;
  }

  /**
   * Serves the member in `mode`: predict (only in a predict-mode room; false otherwise) takes a checkpoint now and
   * sends it before the record of its tick; snapshot starts a fresh encoder, so the first snapshot is full and
   * describes every body.
   */
  setNetMode(mode: NetMode): boolean {
    if (mode === NetMode.Predict) {
      if (!this.feed) return false;
      this.delivery = NetMode.Predict;
      this.checkpoint = { tick: this.feed.tick, message: this.feed.checkpoint() };
      return true;
    }
    if (this.delivery !== NetMode.Snapshot) {
      this.delivery = NetMode.Snapshot;
      this.checkpoint = null;
      this.encoder = new SnapshotEncoder(this.fanOut.format);
      // The client's game state came from its own simulation: the first snapshot carries the whole state again.
      this.heldStateVersion = -1;
    }
    return true;
  }

  /** Where the member's predict stream stands: off (snapshots), on, or a checkpoint waiting to go out first. */
  get predictState(): PredictState {
    if (this.delivery !== NetMode.Predict) return 'off';
    return this.checkpoint === null ? 'on' : 'pending';
  }

  /**
   * Takes over a member whose stream another thread's room served up to the tick before this room's next one: 'on'
   * goes on with the next record (the client has every earlier one), 'pending' sends a checkpoint first.
   */
  continueStream(state: PredictState): void {
    if (state === 'off' || !this.feed) return;
    if (state === 'pending') this.setNetMode(NetMode.Predict);
    else this.delivery = NetMode.Predict;
  }

  takesRecords(): boolean {
    return this.delivery === NetMode.Predict;
  }

  deliverRecord(tick: number, message: Uint8Array): void {
    if (this.delivery !== NetMode.Predict || this.sink.tooFarBehind()) return;
    const cp = this.checkpoint;
    if (cp !== null) {
      if (tick < cp.tick) return; // released late, from before the checkpoint: the checkpoint already holds it
      this.checkpoint = null;
      this.sink.deliver(cp.message, DeliveryKind.Reliable);
    }
    this.sink.deliver(message, DeliveryKind.Reliable);
  }

  deliverEvents(_tick: number, events: readonly SimEvent[]): void {
    // A predicting member derives every event from the confirmed ticks it simulates itself.
    if (!this.encoder || this.delivery === NetMode.Predict || this.sink.tooFarBehind()) return;
    this.sink.deliver(this.fanOut.eventsMessage(events), DeliveryKind.Reliable);
  }

  deliverFrame(frame: WorldFrame): void {
    const encoder = this.encoder;
    if (!encoder || this.delivery === NetMode.Predict || this.sink.tooFarBehind()) return;
    // A full snapshot is on its way and not acked yet: another full one would only repeat it.
    if (!encoder.shouldSend(frame.tick)) return;
    if (this.sink.backedUp()) {
      this.metrics.snapshotsSkipped.inc();
      this.sink.snapshotSkipped();
      return;
    }
    const { message, encoded, stateVersion } = this.fanOut.snapshotFor(encoder, frame, this.heldStateVersion);
    this.heldStateVersion = stateVersion;
    this.sink.deliver(message, DeliveryKind.Snapshot);
    this.metrics.snapshotBytes.observe(message.length);
    this.metrics.snapshotsSent.inc({ kind: encoded.baselineTick === null ? 'full' : 'delta' });
  }

  roomClosed(reason: string): void {
    this.sink.roomClosed(reason);
  }

  removed(reason: string): void {
    this.sink.removed(reason);
  }
}
