// One member's deliveries out of a room: the tick's events (reliable) and its snapshots, encoded by the member's own
// SnapshotEncoder from the room's shared fan-out work and handed to a MemberSink. The same code runs beside a room on
// the main thread and inside a room worker; it never touches a socket.
import type { SnapshotEncoder } from '../shared/protocol/index.ts';
import type { SimEvent } from '../shared/sim/types.ts';
import { DeliveryKind, type MemberSink } from './hosted-room.ts';
import type { ServerMetrics } from './metrics.ts';
import type { RoomMember, WorldFrame } from './room.ts';
import type { SnapshotFanOut } from './snapshot-fan-out.ts';

/** Room-side half of a member: encodes for it and hands the bytes to its sink. */
export class DeliveringMember implements RoomMember {
  /** Set once the welcome is built (it counts the welcome's bodies as known); nothing is sent before. */
  encoder: SnapshotEncoder | null = null;
  private readonly sink: MemberSink;
  private readonly fanOut: SnapshotFanOut;
  private readonly metrics: ServerMetrics;

  constructor(sink: MemberSink, fanOut: SnapshotFanOut, metrics: ServerMetrics) {
    this.sink = sink;
    this.fanOut = fanOut;
    this.metrics = metrics;
  }

  deliverEvents(_tick: number, events: readonly SimEvent[]): void {
    if (!this.encoder || this.sink.tooFarBehind()) return;
    this.sink.deliver(this.fanOut.eventsMessage(events), DeliveryKind.Reliable);
  }

  deliverFrame(frame: WorldFrame): void {
    const encoder = this.encoder;
    if (!encoder || this.sink.tooFarBehind()) return;
    // A full snapshot is on its way and not acked yet: another full one would only repeat it.
    if (!encoder.shouldSend(frame.tick)) return;
    if (this.sink.backedUp()) {
      this.metrics.snapshotsSkipped.inc();
      this.sink.snapshotSkipped();
      return;
    }
    const { message, encoded } = this.fanOut.snapshotFor(encoder, frame);
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
