// Test helper: a small protocol-exact server on a MemoryNetwork and a ManualClock. It ticks at 60 Hz, buffers each
// player's inputs by tick (repeating the last one when none arrived, counting misses), moves one character per
// player from its inputs plus a few scripted bodies, and sends per-client delta snapshots, pongs and events. Welcomes
// carry resume tokens; a hello with a known one gets the same player id back (resumed).
import type { MemoryNetwork, MemoryPeer } from '../../sdk/memory-transport.ts';
import type { ManualClock } from '../../shared/clock.ts';
import { BodyFlag } from '../../shared/physics-data/body-state.ts';
import { encodeServerMessage } from '../../shared/protocol/codec.ts';
import { ByeReason, ErrorCode, PROTOCOL_VERSION } from '../../shared/protocol/opcodes.ts';
import { createSnapshotFormat, snapshotFormatSpec } from '../../shared/protocol/quantization.ts';
import type { HelloMessage } from '../../shared/protocol/client-messages.ts';
import type { ServerMessage } from '../../shared/protocol/server-messages.ts';
import { quantizeFrame, type QuantizedFrame } from '../../shared/protocol/snapshot-frame.ts';
import { SnapshotEncoder } from '../../shared/protocol/snapshot-stream.ts';
import { decodeClientMessage } from '../../shared/protocol/validation.ts';
import { NEUTRAL_INPUT, type InputCommand } from '../../shared/sim/input.ts';
import type { BodyDescriptor, CharacterState, SimEvent } from '../../shared/sim/types.ts';
import { TICK_MS } from '../../shared/tick-rate.ts';

const BOUNDS = { min: { x: -100, y: -10, z: -100 }, max: { x: 100, y: 50, z: 100 } };
/** The server's clock reads this much more than the shared ManualClock (a different origin). */
export const SERVER_CLOCK_OFFSET_MS = 777_777;

/** One connected client as the fake server sees it. */
export interface FakeSession {
  peer: MemoryPeer;
  playerId: number | null;
  room: string | null;
  name: string | null;
  encoder: SnapshotEncoder;
  inputs: Map<number, InputCommand>;
  lastInput: InputCommand;
  firstInputTick: number | null;
  missed: number;
  late: number;
  received: string[];
  /** Snapshot ticks acked, in arrival order: by an ack message or riding on an input message (protocol 7). */
  acked: number[];
  /** Commands applied per tick. */
  applied: Map<number, InputCommand>;
  /** Ticks whose command had arrived in time (the rest repeated the previous one). */
  onTime: Set<number>;
  x: number;
  byeReceived: boolean;
  /** The session's hello, once received. */
  hello: HelloMessage | null;
}

/** Options of FakeServer. */
export interface FakeServerOptions {
  snapshotRateHz?: number;
  /** Bodies moving along x at 1 m/s (ids 1..n). */
  movingBodies?: number;
  /** Version the welcome claims. */
  protocolVersion?: number;
  /** Answer hello with this error (then bye with byeReason and close). */
  refuseWith?: { code: ErrorCode; byeReason: ByeReason } | null;
  /** Answer hello with error + bye room-moved carrying this URL (another server of a fleet hosts the room). */
  moveTo?: string | null;
}

/** A fake room server listening on one URL. */
export class FakeServer {
  readonly url: string;
  readonly sessions: FakeSession[] = [];
  tick = 0;
  /** Added to every reported missedInputTicks (to test the client's lead boost). */
  extraMissed = 0;
  readonly frames = new Map<number, QuantizedFrame>();
  private readonly clock: ManualClock;
  private readonly o: Required<FakeServerOptions>;
  private readonly format = createSnapshotFormat(BOUNDS);
  private nextPlayer = 1;
  private nextToken = 1;
  /** Live resume tokens → player id (single use). */
  private readonly resumeTokens = new Map<string, number>();
  private startMs = 0;
  private running = false;
  private readonly eventsQueue: SimEvent[] = [];

  constructor(clock: ManualClock, net: MemoryNetwork, url: string, opts: FakeServerOptions = {}) {
    this.clock = clock;
    this.url = url;
    this.o = { snapshotRateHz: 20, movingBodies: 3, protocolVersion: PROTOCOL_VERSION, refuseWith: null, moveTo: null, ...opts };
    net.listen(url, (peer) => this.accept(peer));
  }

  /** Starts the 60 Hz tick loop (ticks complete at start + n·TICK_MS). */
  start(): void {
    this.running = true;
    this.startMs = this.clock.nowMs() - this.tick * TICK_MS;
    this.scheduleTick();
  }

  /** Stops ticking. */
  stop(): void {
    this.running = false;
  }

  /** Fractional tick count now, from the server's schedule. */
  exactTick(): number {
    return (this.clock.nowMs() - this.startMs) / TICK_MS;
  }

  /** The session of a player. */
  session(playerId: number): FakeSession {
    const s = this.sessions.find((x) => x.playerId === playerId);
    if (!s) throw new Error(`no session for player ${playerId}`);
    return s;
  }

  /** Sends a message to one session. */
  send(s: FakeSession, m: ServerMessage): void {
    s.peer.send(encodeServerMessage(m));
  }

  /** Says bye with a reason and closes the link. */
  kick(s: FakeSession, reason: ByeReason, message: string): void {
    this.send(s, { type: 'bye', reason, message });
    s.peer.close(4000, message);
  }

  /** Queues an event for every client (sent after the next tick). */
  emit(e: SimEvent): void {
    this.eventsQueue.push(e);
  }

  private scheduleTick(): void {
    const due = this.startMs + (this.tick + 1) * TICK_MS;
    this.clock.setTimer(due - this.clock.nowMs(), () => {
      if (!this.running) return;
      this.step();
      this.scheduleTick();
    });
  }

  private accept(peer: MemoryPeer): void {
    const s: FakeSession = {
      peer,
      playerId: null,
      room: null,
      name: null,
      encoder: new SnapshotEncoder(this.format),
      inputs: new Map(),
      lastInput: { ...NEUTRAL_INPUT },
      firstInputTick: null,
      missed: 0,
      late: 0,
      received: [],
      acked: [],
      applied: new Map(),
      onTime: new Set(),
      x: 0,
      byeReceived: false,
      hello: null,
    };
    this.sessions.push(s);
    peer.onMessage((data) => this.onMessage(s, data));
    peer.onClose(() => {
      const i = this.sessions.indexOf(s);
      if (i >= 0) this.sessions.splice(i, 1);
    });
  }

  private describe(id: number): BodyDescriptor {
    return { id, shape: { kind: 'box', halfExtents: { x: 0.5, y: 0.5, z: 0.5 } }, color: [0.5, 0.5, 0.5], motion: 'dynamic', hidden: false, position: { x: 0, y: 0, z: 0 }, rotation: { x: 0, y: 0, z: 0, w: 1 } };
  }

  private onMessage(s: FakeSession, data: Uint8Array): void {
    const r = decodeClientMessage(data);
    if (!r.ok) {
      s.received.push(`invalid:${r.code}`);
      this.send(s, { type: 'error', code: r.code, message: r.error });
      return;
    }
    const m = r.message;
    s.received.push(m.type);
    switch (m.type) {
      case 'hello': {
        if (this.o.moveTo) {
          s.hello = m;
          this.send(s, { type: 'error', code: ErrorCode.RoomMoved, message: 'hosted elsewhere' });
          this.send(s, { type: 'bye', reason: ByeReason.RoomMoved, message: 'hosted elsewhere', url: this.o.moveTo });
          s.peer.close(1000, 'room-moved');
          return;
        }
        if (this.o.refuseWith) {
          this.send(s, { type: 'error', code: this.o.refuseWith.code, message: `refused: ${this.o.refuseWith.code}` });
          this.kick(s, this.o.refuseWith.byeReason, 'refused');
          return;
        }
        s.hello = m;
        let resumed = false;
        const claimed = m.resumeToken === undefined ? undefined : this.resumeTokens.get(m.resumeToken);
        if (m.resumeToken !== undefined) this.resumeTokens.delete(m.resumeToken);
        if (claimed !== undefined) {
          resumed = true;
          s.playerId = claimed;
          for (const other of this.sessions) if (other !== s && other.playerId === claimed) other.playerId = null;
        } else {
          if (m.resumeToken !== undefined) this.send(s, { type: 'error', code: ErrorCode.ResumeRefused, message: 'cannot resume: unknown token; joining as a new player' });
          s.playerId = this.nextPlayer++;
        }
        const resumeToken = `fakeResume${this.nextToken++}`;
        this.resumeTokens.set(resumeToken, s.playerId);
        s.room = m.room;
        s.name = m.name;
        const dynamicBodies = Array.from({ length: this.o.movingBodies }, (_, i) => this.describe(i + 1));
        s.encoder.markDescriptorsKnown(dynamicBodies.map((d) => d.id));
        this.send(s, {
          type: 'welcome',
          protocolVersion: this.o.protocolVersion,
          playerId: s.playerId,
          roomId: m.room ?? 'default',
          tick: this.tick,
          tickRateHz: 60,
          snapshotRateHz: this.o.snapshotRateHz,
          netMode: 'snapshot',
          inputDelayTicks: 0,
          scenario: { name: 'fake', description: 'a fake room', params: {}, bounds: BOUNDS },
          snapshotFormat: snapshotFormatSpec(this.format),
          staticBodies: [{ id: 0, shape: { kind: 'box', halfExtents: { x: 100, y: 0.5, z: 100 } }, color: [0.2, 0.2, 0.2], motion: 'static', hidden: false, position: { x: 0, y: -0.5, z: 0 }, rotation: { x: 0, y: 0, z: 0, w: 1 } }],
          dynamicBodies,
          resumeToken,
          resumeGraceMs: 30_000,
          resumed,
        });
        if (!resumed) this.emit({ type: 'playerJoined', tick: this.tick, playerId: s.playerId, name: m.name });
        return;
      }
      case 'input':
        if (m.ackTick !== undefined) {
          s.encoder.acknowledge(m.ackTick);
          s.acked.push(m.ackTick);
        }
        m.commands.forEach((c, i) => {
          const t = m.firstTick + i;
          if (t < this.tick) {
            s.late++;
            return;
          }
          if (!s.inputs.has(t)) s.inputs.set(t, c);
          s.firstInputTick = s.firstInputTick === null ? t : Math.min(s.firstInputTick, t);
        });
        return;
      case 'ack':
        s.encoder.acknowledge(m.tick);
        s.acked.push(m.tick);
        return;
      case 'ping':
        this.send(s, { type: 'pong', clientTimeMs: m.clientTimeMs, serverTick: this.tick, serverTimeMs: this.clock.nowMs() + SERVER_CLOCK_OFFSET_MS, missedInputTicks: s.missed + this.extraMissed, roomTicksPerSecond: 60, roomSlow: false });
        return;
      case 'bye':
        s.byeReceived = true;
        s.peer.close(1000, 'bye');
        return;
    }
  }

  private step(): void {
    const t = this.tick;
    for (const s of this.sessions) {
      if (s.playerId === null) continue;
      const c = s.inputs.get(t);
      if (c) {
        s.lastInput = c;
        s.inputs.delete(t);
        s.onTime.add(t);
      } else if (s.firstInputTick !== null && t > s.firstInputTick) {
        s.missed++;
      }
      s.applied.set(t, s.lastInput);
      s.x += (s.lastInput.moveX / 127) * 0.1;
    }
    this.tick++;
    const events = this.eventsQueue.splice(0);
    for (const s of this.sessions) if (s.playerId !== null && events.length > 0) this.send(s, { type: 'events', events });
    if (this.tick % Math.round(60 / this.o.snapshotRateHz) !== 0) return;
    const frame = this.frame();
    this.frames.set(frame.tick, frame);
    for (const s of this.sessions) {
      if (s.playerId === null || !s.encoder.shouldSend(frame.tick)) continue;
      const out = s.encoder.encode(frame, (id) => this.describe(id));
      this.send(s, { type: 'snapshot', bytes: out.bytes, descriptors: out.descriptors });
    }
  }

  private frame(): QuantizedFrame {
    const n = this.o.movingBodies;
    const ids = new Uint32Array(n);
    const states = new Float32Array(n * 13);
    const flags = new Uint8Array(n);
    for (let i = 0; i < n; i++) {
      ids[i] = i + 1;
      states.set([this.tick / 60 + i, 1, -i, 0, 0, 0, 1], i * 13);
      flags[i] = BodyFlag.Dynamic | BodyFlag.Active;
    }
    const characters: CharacterState[] = this.sessions
      .filter((s) => s.playerId !== null)
      .map((s) => ({ playerId: s.playerId!, bodyId: 1000 + s.playerId!, position: { x: s.x, y: 0, z: 0 }, velocity: { x: 0, y: 0, z: 0 }, yaw: 0, pitch: 0, groundState: 'ground', buttons: s.lastInput.buttons }));
    return quantizeFrame(this.format, this.tick, { count: n, ids, states, flags }, characters);
  }
}
