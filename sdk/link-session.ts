// One connection's lifetime inside the client: hello → welcome, pings and clock sync, the input loop (target tick =
// estimated server tick at arrival + adaptive lead, with redundancy), snapshot decode → ack → interpolation, events
// and errors. NetClient creates a new LinkSession per (re)connection and owns reconnect policy and public events.
import type { GameStateValue } from '../shared/sim/game-state.ts';
import type { Clock, TimerHandle } from '../shared/clock.ts';
import type { ClientMessage } from '../shared/protocol/client-messages.ts';
import { encodeClientMessage } from '../shared/protocol/codec.ts';
import { PROTOCOL_VERSION } from '../shared/protocol/opcodes.ts';
import { snapshotFormatFromSpec, type SnapshotFormat } from '../shared/protocol/quantization.ts';
import { decodeServerMessage } from '../shared/protocol/server-message-decoder.ts';
import type { ErrorMessage, ServerByeMessage, ServerMessage, WelcomeMessage } from '../shared/protocol/server-messages.ts';
import { dequantizeFrame, type QuantizedFrame, type SnapshotView } from '../shared/protocol/snapshot-frame.ts';
import { SnapshotDecoder } from '../shared/protocol/snapshot-stream.ts';
import type { InputCommand } from '../shared/sim/input.ts';
import type { BodyDescriptor, SimEvent } from '../shared/sim/types.ts';
import { ClockSync } from './clock-sync.ts';
import { AckCarrier, InputLead, InputSender, type InputLeadOptions } from './input-sender.ts';
import { InterpolationBuffer, type InterpolatedFrame, type InterpolationOptions } from './interpolation.ts';
import { PredictSession, type PredictedFrame, type PredictOptions } from './prediction/predict-session.ts';
import type { Transport, TransportFactory } from './transport.ts';

/** The input pump's period, in ticks. */
const PUMP_SPACING_TICKS = 0.5;

/** A decoded snapshot as the client reports it. */
export interface SnapshotInfo {
  tick: number;
  baselineTick: number | null;
  /** Size of the whole message on the wire (bytes, without WebSocket framing). */
  sizeBytes: number;
  /** Descriptors of bodies this snapshot introduced. */
  descriptors: BodyDescriptor[];
  /** The exact quantized frame the server encoded. */
  frame: QuantizedFrame;
  /** Its float view. */
  view: SnapshotView;
}

/** What a LinkSession tells its owner. */
export interface LinkSessionHandlers {
  welcome(w: WelcomeMessage): void;
  snapshot(s: SnapshotInfo): void;
  /** A snapshot carried the room's game state (values in the welcome's state-field order). */
  gameState(values: GameStateValue[]): void;
  events(events: SimEvent[]): void;
  serverError(e: ErrorMessage): void;
  bye(b: ServerByeMessage): void;
  protocolError(message: string): void;
  /** The link is gone; called once. */
  closed(info: LinkClosedInfo): void;
}

/** How a link ended. */
export interface LinkClosedInfo {
  code: number;
  reason: string;
  welcomed: boolean;
  bye: ServerByeMessage | null;
  /** An error message the server sent before any welcome (e.g. version mismatch, room full). */
  errorBeforeWelcome: ErrorMessage | null;
  /** Closed by the client itself. */
  byClient: boolean;
  /** Whether the connection ever opened (false: nothing answered, e.g. the server is down or restarting). */
  opened: boolean;
}

/** Settings a LinkSession needs. */
export interface LinkSessionOptions {
  url: string;
  name: string;
  room: string | null;
  transport: TransportFactory;
  clock: Clock;
  inputRedundancy: number;
  pingIntervalMs: number;
  initialPings: number;
  interpolation: Partial<InterpolationOptions>;
  lead: Partial<InputLeadOptions>;
  /** The command to send until setInput changes it (kept across reconnects). */
  input: InputCommand;
  /** Seat token for the hello (servers that admit only reserved seats). */
  seatToken?: string;
  /** Resume token of the previous link's welcome: ask for the same player back. */
  resumeToken?: string;
  /** Predicted play in rooms that offer it. */
  predict?: PredictOptions;
}

/** Counters of one link. */
export interface LinkCounters {
  bytesIn: number;
  bytesOut: number;
  messagesIn: number;
  snapshots: number;
  snapshotsFailed: number;
  inputMessages: number;
  /** Snapshot acks that went out alone (most ride on input messages). */
  ackMessages: number;
  pings: number;
  pongs: number;
}

const INITIAL_PING_SPACING_MS = 100;

/** Whether a command moves or presses differently from the one fixed for a tick (look angles aside). */
function movesDiffer(a: InputCommand, fixed: InputCommand | undefined): boolean {
  return fixed !== undefined && (a.moveX !== fixed.moveX || a.moveZ !== fixed.moveZ || a.buttons !== fixed.buttons);
}

/** One connection from hello to close. */
export class LinkSession {
  private readonly o: LinkSessionOptions;
  private readonly h: LinkSessionHandlers;
  private readonly transport: Transport;
  private timers: TimerHandle[] = [];
  private welcomeMsg: WelcomeMessage | null = null;
  private format: SnapshotFormat | null = null;
  private decoder: SnapshotDecoder | null = null;
  private interp: InterpolationBuffer | null = null;
  private sync: ClockSync | null = null;
  private readonly sender: InputSender;
  private readonly acks = new AckCarrier();
  private lead: InputLead | null = null;
  private missedInputTicks: number | null = null;
  /** The furthest tick the input clock has asked for on this link (-1: none yet). */
  private highestClockTarget = -1;
  private roomPace: { ticksPerSecond: number; slow: boolean } | null = null;
  private bye: ServerByeMessage | null = null;
  private errorBeforeWelcome: ErrorMessage | null = null;
  private closing = false;
  private opened = false;
  private ended = false;
  private pingsSent = 0;
  private newestFrame: QuantizedFrame | null = null;
  private predictSession: PredictSession | null = null;
  readonly counters: LinkCounters = { bytesIn: 0, bytesOut: 0, messagesIn: 0, snapshots: 0, snapshotsFailed: 0, inputMessages: 0, ackMessages: 0, pings: 0, pongs: 0 };
  /** Recent (time, bytes) of received messages, for kbps. */
  private readonly inLog: Array<[number, number]> = [];

  constructor(opts: LinkSessionOptions, handlers: LinkSessionHandlers) {
    this.o = opts;
    this.h = handlers;
    this.sender = new InputSender({ redundancy: opts.inputRedundancy });
    this.sender.setCommand(opts.input);
    this.transport = opts.transport(opts.url, {
      open: () => {
        this.opened = true;
        this.send({ type: 'hello', version: PROTOCOL_VERSION, name: opts.name, room: opts.room, seatToken: opts.seatToken, resumeToken: opts.resumeToken });
      },
      message: (data) => this.receive(data),
      close: (code, reason) => this.end(code, reason),
    });
  }

  /** The welcome of this link, once received. */
  get welcome(): WelcomeMessage | null {
    return this.welcomeMsg;
  }

  /** The snapshot quantization format (after welcome). */
  get snapshotFormat(): SnapshotFormat | null {
    return this.format;
  }

  /** Clock sync of this link (after welcome). */
  get clockSync(): ClockSync | null {
    return this.sync;
  }

  /** The input lead in ticks (after welcome). */
  get leadTicks(): number | null {
    return this.lead?.leadTicks ?? null;
  }

  /** The newest tick an input was generated for. */
  get newestInputTick(): number {
    return this.sender.newestTick;
  }

  /** The room's ticks per second and whether it runs slowed (last pong); null before one. */
  get serverRoomPace(): { ticksPerSecond: number; slow: boolean } | null {
    return this.roomPace;
  }

  /** Ticks the server reported it had to repeat our input (last pong). */
  get serverMissedInputTicks(): number | null {
    return this.missedInputTicks;
  }

  /** The newest decoded frame. */
  get latestFrame(): QuantizedFrame | null {
    return this.newestFrame;
  }

  /** Predicted play on this link (null: the room serves snapshots or the client did not ask to predict). */
  get prediction(): PredictSession | null {
    return this.predictSession;
  }

  /** The interpolation buffer (after welcome). */
  get interpolation(): InterpolationBuffer | null {
    return this.interp;
  }

  /** Received kilobits per second over the last second. */
  kbpsIn(nowMs: number): number {
    while (this.inLog.length > 0 && this.inLog[0][0] < nowMs - 1000) this.inLog.shift();
    let bytes = 0;
    for (const [, b] of this.inLog) bytes += b;
    return (bytes * 8) / 1000;
  }

  /** Sends a game message now (after the welcome). */
  sendGameMessage(name: string, payload: number[]): void {
    // A predicting client applies it on its next local tick and asks the server for the same tick.
    const tick = this.predictSession?.onOwnMessage(name, payload) ?? null;
    this.send(tick === null ? { type: 'game', name, payload } : { type: 'game', name, payload, tick });
  }

  /** Sets the command for ticks from now on. */
  setInput(cmd: InputCommand): void {
    this.sender.setCommand(cmd);
  }

  /** The interpolated world at a local time. */
  sample(nowMs: number): InterpolatedFrame | null {
    return this.interp?.sample(nowMs) ?? null;
  }

  /** Says bye and closes (the closed handler still runs once, with byClient). */
  close(): void {
    if (this.closing || this.ended) return;
    this.closing = true;
    this.send({ type: 'bye' });
    this.clearTimers();
    this.transport.close(1000, 'client closed');
  }

  private send(m: ClientMessage): void {
    if (this.ended) return;
    const bytes = encodeClientMessage(m);
    this.counters.bytesOut += bytes.length;
    this.transport.send(bytes);
  }

  private schedule(delayMs: number, fn: () => void): void {
    const handle = this.o.clock.setTimer(delayMs, () => {
      this.timers = this.timers.filter((t) => t !== handle);
      if (!this.ended && !this.closing) fn();
    });
    this.timers.push(handle);
  }

  private clearTimers(): void {
    for (const t of this.timers) this.o.clock.clearTimer(t);
    this.timers = [];
  }

  private end(code: number, reason: string): void {
    if (this.ended) return;
    this.ended = true;
    this.clearTimers();
    this.predictSession?.dispose();
    this.h.closed({ code, reason, welcomed: this.welcomeMsg !== null, bye: this.bye, errorBeforeWelcome: this.errorBeforeWelcome, byClient: this.closing, opened: this.opened });
  }

  private receive(data: Uint8Array): void {
    if (this.ended) return;
    const now = this.o.clock.nowMs();
    this.counters.bytesIn += data.length;
    this.counters.messagesIn++;
    this.inLog.push([now, data.length]);
    const r = decodeServerMessage(data);
    if (!r.ok && r.serverVersion !== undefined && this.welcomeMsg === null) {
      this.versionMismatch(r.serverVersion);
      return;
    }
    if (!r.ok) {
      this.h.protocolError(`undecodable server message: ${r.error}`);
      return;
    }
    this.handle(r.message, data.length, now);
  }

  private handle(m: ServerMessage, sizeBytes: number, now: number): void {
    switch (m.type) {
      case 'welcome':
        this.onWelcome(m, now);
        return;
      case 'pong':
        if (!this.sync) return;
        this.counters.pongs++;
        this.sync.addSample({ sentLocalMs: m.clientTimeMs, receivedLocalMs: now, serverTick: m.serverTick, serverTimeMs: m.serverTimeMs });
        this.missedInputTicks = m.missedInputTicks;
        this.roomPace = { ticksPerSecond: m.roomTicksPerSecond, slow: m.roomSlow };
        return;
      case 'snapshot':
        this.onSnapshot(m.bytes, m.descriptors, sizeBytes, now);
        if (m.state !== undefined && this.welcomeMsg !== null) this.h.gameState(m.state);
        return;
      case 'events':
        this.h.events(m.events);
        return;
      case 'error':
        if (this.welcomeMsg === null) this.errorBeforeWelcome = m;
        this.h.serverError(m);
        return;
      case 'bye':
        this.bye = m;
        this.h.bye(m);
        return;
      case 'checkpoint':
        if (this.predictSession) this.predictSession.onCheckpoint(m);
        else this.h.protocolError('a checkpoint arrived although this client does not predict');
        return;
      case 'record':
        if (this.predictSession) this.predictSession.onRecord(m);
        else this.h.protocolError('a record arrived although this client does not predict');
        return;
    }
  }

  private onWelcome(w: WelcomeMessage, now: number): void {
    if (this.welcomeMsg !== null) {
      this.h.protocolError('a second welcome on one connection was ignored');
      return;
    }
    if (w.protocolVersion !== PROTOCOL_VERSION) {
      this.versionMismatch(w.protocolVersion);
      return;
    }
    let format: SnapshotFormat;
    try {
      format = snapshotFormatFromSpec(w.scenario.bounds, w.snapshotFormat);
      if (!(w.tickRateHz > 0) || !(w.snapshotRateHz > 0)) throw new Error(`bad rates ${w.tickRateHz} / ${w.snapshotRateHz} Hz`);
    } catch (e) {
      this.h.protocolError(`unusable welcome: ${(e as Error).message}`);
      this.transport.close(1002, 'unusable welcome');
      return;
    }
    this.welcomeMsg = w;
    this.format = format;
    this.decoder = new SnapshotDecoder(format);
    this.sync = new ClockSync({ tickRateHz: w.tickRateHz });
    this.sync.seed(w.tick, now);
    this.lead = new InputLead({ tickRateHz: w.tickRateHz, ...this.o.lead });
    this.interp = new InterpolationBuffer({ tickRateHz: w.tickRateHz, snapshotRateHz: w.snapshotRateHz, ...this.o.interpolation });
    this.h.welcome(w);
    if (this.o.predict && w.netMode === 'predict') {
      this.predictSession = new PredictSession(w, this.o.predict, {
        send: (msg) => this.send(msg),
        nowMs: () => this.o.clock.nowMs(),
        events: (events) => this.h.events(events),
        gameState: (values) => this.h.gameState(values),
        protocolError: (message) => this.h.protocolError(message),
        fellBack: (reason) => this.h.protocolError(`prediction stopped, back to snapshots: ${reason}`),
      });
    }
    this.ping();
    this.pump();
  }

  /** The server speaks another protocol version: nothing it sends can be trusted to mean what we think. */
  private versionMismatch(serverVersion: number): void {
    this.errorBeforeWelcome = { type: 'error', code: 'version-mismatch', message: `the server speaks protocol ${serverVersion} and this client ${PROTOCOL_VERSION}: use a client built for protocol ${serverVersion}` };
    this.h.serverError(this.errorBeforeWelcome);
    this.transport.close(1002, 'protocol version mismatch');
  }

  private ping(): void {
    this.counters.pings++;
    this.send({ type: 'ping', clientTimeMs: this.o.clock.nowMs() });
    this.pingsSent++;
    this.schedule(this.pingsSent < this.o.initialPings ? INITIAL_PING_SPACING_MS : this.o.pingIntervalMs, () => this.ping());
  }

  /** The input loop: runs twice per tick, sends when the target tick advanced. */
  private pump(): void {
    this.inputStep();
    this.schedule(this.sync!.tickMs * PUMP_SPACING_TICKS, () => this.pump());
  }

  /**
   * A predicting client's frame: the input loop's step now (fix and send the commands of ticks that came due, run the
   * local simulation to them), so the drawn world holds the newest own command whatever the timers' phase.
   */
  predictedFrame(): PredictedFrame | null {
    const p = this.predictSession;
    if (!p || !p.active || this.ended || this.closing) return null;
    this.inputStep(true);
    return p.frame();
  }

  /**
   * `atFrame`: a frame is about to be drawn. When the move axes or buttons changed since the newest fixed tick, the
   * next tick is fixed with them at once, so the frame drawn right after a key has simulated the key's tick: at most
   * one tick past the furthest the clock has asked for. The clock's target can sit ticks behind the newest fixed tick
   * (the estimate moves back when the smoothed round trip falls after a retransmitted pong, or the jitter margin
   * shrinks); measuring from its furthest keeps a stick that changes every frame from running the lead away. A look
   * change alone waits for the clock (the camera turns locally), so steady mouse movement does not keep the lead a
   * tick longer.
   */
  private inputStep(atFrame = false): void {
    const sync = this.sync!;
    const lead = this.lead!;
    const now = this.o.clock.nowMs();
    lead.update(sync.jitterMs, this.missedInputTicks, now);
    const oneWayMs = (sync.rttMs ?? 0) / 2;
    // The pump runs every half tick, so the command for tick T first goes out within half a tick after the server's
    // tick count (at arrival) passes T: T is then the next tick the server runs, at least half a tick away. The lead
    // (jitter margin + boost) only moves the target further when it needs more than that half tick.
    // A predicting client's input delay: commands go out for ticks this much later than the local present.
    const p = this.predictSession;
    const delay = p?.active ? p.inputDelayTicks : 0;
    let target = Math.floor(sync.serverTickAt(now + oneWayMs) + Math.max(0, lead.leadTicks - PUMP_SPACING_TICKS)) + delay;
    const newest = this.sender.newestTick;
    this.highestClockTarget = Math.max(this.highestClockTarget, target);
    if (atFrame && newest >= 0 && newest >= target && newest <= this.highestClockTarget && movesDiffer(this.sender.command, this.sender.commandFor(newest))) target = newest + 1;
    const msg = target >= 0 ? this.sender.update(target) : null;
    if (msg !== null) {
      const ackTick = this.acks.carry();
      if (ackTick !== undefined) msg.ackTick = ackTick;
      this.counters.inputMessages++;
      this.send(msg);
    } else {
      const ackTick = this.acks.alone();
      if (ackTick !== null) {
        this.counters.ackMessages++;
        this.send({ type: 'ack', tick: ackTick });
      }
    }
    // The local simulation runs to the newest tick the sender fixed, less the delay: with no delay, the own command of
    // that tick is in it.
    if (target >= 0) p?.advance(this.sender.newestTick + 1 - delay, (t) => this.sender.commandFor(t));
  }

  private onSnapshot(bytes: Uint8Array, descriptors: BodyDescriptor[], sizeBytes: number, now: number): void {
    if (!this.decoder || !this.format || !this.interp) {
      this.h.protocolError('snapshot before welcome ignored');
      return;
    }
    let decoded;
    try {
      decoded = this.decoder.decode(bytes);
    } catch (e) {
      this.counters.snapshotsFailed++;
      this.h.protocolError(`snapshot not decoded: ${(e as Error).message}`);
      return;
    }
    const frame = decoded.frame;
    this.counters.snapshots++;
    this.acks.decoded(frame.tick); // rides on the next input message (or goes alone within a tick)
    if (this.newestFrame === null || frame.tick > this.newestFrame.tick) this.newestFrame = frame;
    const view = dequantizeFrame(this.format, frame);
    this.interp.push(view, now);
    this.h.snapshot({ tick: frame.tick, baselineTick: decoded.baselineTick, sizeBytes, descriptors, frame, view });
  }
}
