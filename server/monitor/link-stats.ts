// What the monitor shows about one client link, kept by its session: the player's name, bytes received, the lead of
// its newest input over the room's tick, and a round-trip time measured from each snapshot sent to its ack (the
// client library acks a snapshot as soon as it has decoded it). Plain counters: no timers, no allocation per message.
import { ServerOpcode } from '../../shared/protocol/opcodes.ts';
import { readSnapshotHeader } from '../../shared/protocol/snapshot-codec.ts';

const SNAPSHOT_OPCODE: number = ServerOpcode.Snapshot;

/** The snapshot bytes inside a framed snapshot message (raw `[18, …]` or msgpack `[18, <bin>, …]`), or null. */
function snapshotPayload(bytes: Uint8Array): Uint8Array | null {
  const head = bytes[0];
  if (head === undefined) return null;
  if (head === SNAPSHOT_OPCODE) return bytes.length > 1 ? bytes.subarray(1) : null;
  let i = 1;
  if (head === 0xdc) i += 2;
  else if (head === 0xdd) i += 4;
  else if (head < 0x90 || head > 0x9f) return null;
  if (bytes[i++] !== SNAPSHOT_OPCODE) return null;
  const bin = bytes[i++];
  let length: number;
  // Read byte by byte: no DataView allocated per member and snapshot.
  if (bin === 0xc4 && i + 1 <= bytes.length) length = bytes[i++];
  else if (bin === 0xc5 && i + 2 <= bytes.length) {
    length = (bytes[i] << 8) | bytes[i + 1];
    i += 2;
  } else if (bin === 0xc6 && i + 4 <= bytes.length) {
    length = (bytes[i] * 0x1000000 + ((bytes[i + 1] << 16) | (bytes[i + 2] << 8) | bytes[i + 3])) >>> 0;
    i += 4;
  } else return null;
  if (i + length > bytes.length) return null;
  return bytes.subarray(i, i + length);
}

/**
 * The tick of a framed snapshot message, or null when the bytes do not start like one. Reads only the snapshot's
 * header (shared/protocol/snapshot-codec.ts); `referenceTick`, the previous snapshot's tick, completes a delta's tick.
 */
export function snapshotTick(bytes: Uint8Array, referenceTick: number | null): number | null {
  const payload = snapshotPayload(bytes);
  if (payload === null) return null;
  try {
    return readSnapshotHeader(payload, referenceTick).tick;
  } catch {
    return null;
  }
}

/** How many sent snapshots wait for their ack (older ones are forgotten: their ack no longer measures anything). */
const PENDING_ACKS = 64;

/** Counters of one link. */
export class LinkStats {
  /** The player's display name once joined. */
  name = '';
  /** Bytes received from the client (every frame). */
  bytesIn = 0;
  /** Newest input tick minus the room's next tick at arrival; null before the first input. */
  inputLeadTicks: number | null = null;
  /** Smoothed snapshot → ack round trip (ms); null before the first ack. */
  rttMs: number | null = null;
  /** The tick of the newest snapshot sent; null before the first. */
  lastSnapshotTick: number | null = null;
  private readonly sentTick = new Int32Array(PENDING_ACKS).fill(-1);
  private readonly sentMs = new Float64Array(PENDING_ACKS);

  /** A snapshot for `tick` went out at `nowMs`. */
  snapshotSent(tick: number, nowMs: number): void {
    this.lastSnapshotTick = tick;
    const slot = tick % PENDING_ACKS;
    this.sentTick[slot] = tick;
    this.sentMs[slot] = nowMs;
  }

  /** The client acked the snapshot of `tick` at `nowMs` (unknown or repeated acks are ignored). */
  acked(tick: number, nowMs: number): void {
    if (!Number.isInteger(tick) || tick < 0) return;
    const slot = tick % PENDING_ACKS;
    if (this.sentTick[slot] !== tick) return;
    this.sentTick[slot] = -1;
    const sample = Math.max(0, nowMs - this.sentMs[slot]);
    this.rttMs = this.rttMs === null ? sample : this.rttMs + (sample - this.rttMs) / 8;
  }

  /** An input batch arrived whose newest command is for `newestTick` while the room is about to simulate `roomTick`. */
  inputArrived(newestTick: number, roomTick: number): void {
    this.inputLeadTicks = newestTick - roomTick;
  }
}
