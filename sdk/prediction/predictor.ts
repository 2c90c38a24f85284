// The rollback core of a predicting client: a local Simulation started from the server's checkpoint runs ahead to the
// present with the player's own commands and everyone else's last confirmed command; each confirmed record is
// checked against what was predicted for its tick, and a difference rolls back to that tick and re-simulates to the
// present. The own game messages are applied on the next predicted tick (own-messages.ts). Confirmed ticks yield the
// authoritative events and game state; every hash the server sends is compared. No timers, no sockets:
// predict-session.ts drives it.
import type { PlayerInputState } from '../../shared/protocol/record-delta.ts';
import { RecordDeltaCoder } from '../../shared/protocol/record-delta.ts';
import { canonicalGame } from '../../shared/protocol/record-game-bits.ts';
import type { GameInputField } from '../../shared/sim/game-input.ts';
import type { GameMessage, GameMessageKind } from '../../shared/sim/game-messages.ts';
import type { GameStateValue } from '../../shared/sim/game-state.ts';
import { carriesHash, type RecordMessage } from '../../shared/protocol/predict-messages.ts';
import { sameInput, type InputCommand } from '../../shared/sim/input.ts';
import type { Checkpoint } from '../../shared/sim/checkpoint.ts';
import { RollbackWindow } from '../../shared/sim/rollback-window.ts';
import type { BodyDescriptor, CharacterState, PlayerCommand, SimEvent, TickInputRecord } from '../../shared/sim/types.ts';
import { OwnMessages } from './own-messages.ts';

/**
 * Default of how many ticks the prediction may run ahead of the newest confirmed tick (1 s). Over a link with 50 ms
 * each way, 10 ms jitter and 2% loss retransmitted as on TCP, the present ran up to 36 ticks ahead; at a cap below
 * that the own newest command waits for the server before it is simulated.
 */
export const DEFAULT_MAX_AHEAD_TICKS = 60;

/** The part of Simulation a predicting client drives (shared/sim/simulation.ts satisfies it). */
export interface PredictSimulation {
  readonly tick: number;
  step(record: TickInputRecord): SimEvent[];
  stateHash(): string;
  saveCheckpoint(): Checkpoint;
  restoreCheckpoint(cp: Checkpoint): void;
  restoreCheckpointBytes(bytes: Uint8Array): void;
  playerIds(): number[];
  characters(): CharacterState[];
  readBodyStates(): { count: number; ids: Uint32Array; states: Float32Array; flags: Uint8Array };
  bodyDescriptor(id: number): BodyDescriptor | undefined;
  descriptors(): BodyDescriptor[];
  destroy(): void;
  /** The scenario's game input fields, message kinds and state fields (absent or empty: it uses no game API). */
  readonly gameInputFields?: readonly GameInputField[];
  readonly gameMessageKinds?: readonly GameMessageKind[];
  readonly gameStateFields?: readonly unknown[];
  /** The game state now, in field order. */
  gameStateValues?(): GameStateValue[];
}

/** What one predicted tick used and produced, until the tick is confirmed. */
interface Slot {
  record: TickInputRecord;
  events: SimEvent[];
  hash: string | null;
  /** The game state after the tick (null: the scenario declares none). */
  state: GameStateValue[] | null;
}

/** What advance() did this time. */
export interface AdvanceReport {
  /** Ticks re-simulated after a misprediction (0: none). */
  rollbackTicks: number;
  /** Ticks stepped in all (confirmed catch-up, re-simulation and new predictions). */
  steppedTicks: number;
  /** Whether a rollback happened (the predicted world was corrected). */
  corrected: boolean;
}

/** Callbacks of a Predictor. */
export interface PredictorHandlers {
  /** Events of ticks just confirmed, in tick order (authoritative: the server's simulation produced the same). */
  confirmedEvents(events: SimEvent[]): void;
  /** The game state after a confirmed tick, when it differs from the last one given (and once at the start). */
  confirmedState?(values: GameStateValue[]): void;
  /** The server's hash of a confirmed tick differs from ours. */
  desync(tick: number, ours: string, theirs: string): void;
  /** Our state hash after a confirmed tick that carries one (whether or not the server's came with it). */
  confirmedHash?(tick: number, hash: string): void;
}

function sameMessages(a: readonly GameMessage[] | undefined, b: readonly GameMessage[] | undefined): boolean {
  const x = a ?? [];
  const y = b ?? [];
  return x.length === y.length && x.every((m, i) => m.playerId === y[i].playerId && m.name === y[i].name && m.payload.length === y[i].payload.length && m.payload.every((v, j) => v === y[i].payload[j]));
}

function sameState(a: readonly GameStateValue[], b: readonly GameStateValue[]): boolean {
  return a.length === b.length && a.every((v, i) => v === b[i]);
}

function sameRecord(predicted: TickInputRecord, confirmed: TickInputRecord): boolean {
  if (confirmed.leaves.length > 0 || confirmed.joins.length > 0 || predicted.commands.length !== confirmed.commands.length) return false;
  if (!sameMessages(predicted.messages, confirmed.messages)) return false;
  for (let i = 0; i < confirmed.commands.length; i++) {
    const a = predicted.commands[i];
    const b = confirmed.commands[i];
    if (a.playerId !== b.playerId || !sameInput(a.input, b.input)) return false;
  }
  return true;
}

/** Rollback prediction over one simulation, from one checkpoint (a resync builds a new Predictor). */
export class Predictor {
  readonly sim: PredictSimulation;
  readonly playerId: number;
  /** Most ticks the prediction runs ahead of the newest confirmed tick. */
  readonly maxAheadTicks: number;
  private readonly window: RollbackWindow;
  private readonly coder: RecordDeltaCoder;
  private readonly handlers: PredictorHandlers;
  private readonly slots = new Map<number, Slot>();
  private readonly queue: Array<{ record: TickInputRecord; hash: string | null }> = [];
  /** The next tick a record will arrive for. */
  private nextRecordTick: number;
  /** The oldest tick not yet confirmed (every tick before it matches the server). */
  private confirmed: number;
  /** Confirmed records from the window's oldest checkpoint on (a rollback re-steps them up to the mismatch). */
  private readonly confirmedRecords = new Map<number, TickInputRecord>();
  private lastOwn: InputCommand | null = null;
  private verified = 0;
  /** The own command each unconfirmed tick was predicted with (re-simulation reuses it). */
  private readonly ownHistory = new Map<number, InputCommand>();
  private readonly ownMessages: OwnMessages;
  private readonly gameFields: readonly GameInputField[];
  private readonly hasState: boolean;
  private lastState: GameStateValue[] | null = null;

  /**
   * `checkpointEveryTicks`: save a fast checkpoint every this many ticks (1: every tick). In big scenes saving costs
   * more than stepping; a rollback then re-steps up to this many − 1 confirmed ticks from the checkpoint before it.
   */
  constructor(sim: PredictSimulation, checkpoint: { tick: number; inputs: PlayerInputState[] }, playerId: number, handlers: PredictorHandlers, maxAheadTicks = DEFAULT_MAX_AHEAD_TICKS, checkpointEveryTicks = 1) {
    this.sim = sim;
    this.playerId = playerId;
    this.handlers = handlers;
    this.maxAheadTicks = maxAheadTicks;
    this.window = new RollbackWindow(sim, maxAheadTicks + checkpointEveryTicks + 2, checkpointEveryTicks);
    this.gameFields = sim.gameInputFields ?? [];
    this.coder = new RecordDeltaCoder(checkpoint.inputs, { fields: this.gameFields, kinds: sim.gameMessageKinds ?? [] });
    this.ownMessages = new OwnMessages(playerId, 2 * maxAheadTicks);
    this.hasState = (sim.gameStateFields?.length ?? 0) > 0 && typeof sim.gameStateValues === 'function';
    this.nextRecordTick = checkpoint.tick;
    this.confirmed = checkpoint.tick;
    if (sim.tick !== checkpoint.tick) throw new Error(`Predictor: the simulation is at tick ${sim.tick}, the checkpoint at ${checkpoint.tick}`);
  }

  /** The game state at the checkpoint (null: the scenario declares none); later states come through confirmedState. */
  startState(): GameStateValue[] | null {
    if (!this.hasState) return null;
    this.lastState = this.sim.gameStateValues!();
    return this.lastState;
  }

  /**
   * An own game message being sent: applied on the next predicted tick (returned: the tick to ask the server for),
   * until the server's record says otherwise.
   */
  sendMessage(name: string, payload: readonly number[]): number {
    this.ownMessages.add(name, payload, this.sim.tick);
    return this.sim.tick;
  }

  /** Own game messages sent and not yet seen in a confirmed record. */
  get pendingMessages(): number {
    return this.ownMessages.size;
  }

  /** The oldest unconfirmed tick: ticks before it are the server's. */
  get confirmedTick(): number {
    return this.confirmed;
  }

  /** The tick the local simulation will step next (ticks simulated so far). */
  get presentTick(): number {
    return this.sim.tick;
  }

  /** Server hashes that matched the local simulation's. */
  get hashesVerified(): number {
    return this.verified;
  }

  /** Confirmed records received but not yet applied. */
  get queuedRecords(): number {
    return this.queue.length;
  }

  /** Decodes the next confirmed record (throws a clear Error for a record that does not fit the stream). */
  receive(msg: RecordMessage): void {
    const tick = this.nextRecordTick;
    if ((tick & 0xff) !== msg.tickLow) throw new Error(`record for tick …${msg.tickLow} (mod 256) arrived, tick ${tick} was expected`);
    const record = this.coder.decode(tick, msg.bits, msg.joins);
    this.nextRecordTick = tick + 1;
    this.queue.push({ record, hash: msg.hash });
  }

  /**
   * Applies the queued confirmed records (rolling back on a misprediction) and predicts up to `targetTick`
   * (exclusive: the simulation ends at tick targetTick), with `ownCommand(tick)` for the player's own ticks.
   * `corrected` runs after a rollback has re-simulated back to the tick the simulation was at before (the same tick,
   * corrected: what a renderer compares), before any new tick is predicted.
   */
  advance(targetTick: number, ownCommand: (tick: number) => InputCommand | undefined, corrected?: () => void): AdvanceReport {
    const present = this.sim.tick;
    let rollbackFrom: number | null = null;
    let restoredFrom = present;
    let stepped = 0;
    for (const { record, hash } of this.queue.splice(0)) {
      const tick = record.tick;
      if (rollbackFrom === null && tick < this.sim.tick) {
        const slot = this.slots.get(tick)!;
        if (sameRecord(slot.record, record)) {
          this.confirm(tick, slot, hash);
          continue;
        }
        rollbackFrom = tick;
        const from = this.window.latestAtOrBefore(tick)!;
        restoredFrom = from;
        this.window.restore(from);
        for (const t of [...this.slots.keys()]) if (t >= tick) this.slots.delete(t);
        for (let t = from; t < tick; t++) {
          this.window.step(this.confirmedRecords.get(t)!);
          stepped++;
        }
      }
      this.stepSlot(record);
      stepped++;
      this.confirm(tick, this.slots.get(tick)!, hash);
    }
    const end = Math.min(Math.max(targetTick, present), this.confirmed + this.maxAheadTicks);
    while (this.sim.tick < Math.min(present, end)) {
      this.stepSlot(this.predictedRecord(this.sim.tick, ownCommand));
      stepped++;
    }
    if (rollbackFrom !== null && rollbackFrom < present && this.sim.tick === present) corrected?.();
    while (this.sim.tick < end) {
      this.stepSlot(this.predictedRecord(this.sim.tick, ownCommand));
      stepped++;
    }
    const oldest = this.window.latestAtOrBefore(this.confirmed);
    if (oldest !== null) {
      this.window.forgetBefore(oldest);
      for (const t of this.confirmedRecords.keys()) if (t < oldest) this.confirmedRecords.delete(t);
    }
    for (const t of this.ownHistory.keys()) if (t < this.confirmed) this.ownHistory.delete(t);
    const rollbackTicks = rollbackFrom === null ? 0 : Math.max(0, Math.min(present, this.sim.tick) - restoredFrom);
    return { rollbackTicks, steppedTicks: stepped, corrected: rollbackFrom !== null && rollbackFrom < present };
  }

  /** Frees the rollback checkpoints (the simulation belongs to the caller). */
  dispose(): void {
    this.window.dispose();
    this.slots.clear();
    this.confirmedRecords.clear();
    this.ownHistory.clear();
    this.ownMessages.clear();
    this.queue.length = 0;
  }

  private predictedRecord(tick: number, ownCommand: (tick: number) => InputCommand | undefined): TickInputRecord {
    const commands: PlayerCommand[] = [];
    for (const id of this.sim.playerIds()) {
      let input: InputCommand | undefined;
      if (id === this.playerId) {
        input = this.ownHistory.get(tick) ?? ownCommand(tick) ?? this.lastOwn ?? this.coder.inputOf(id);
        if (input) {
          this.lastOwn = input;
          this.ownHistory.set(tick, input);
        }
      } else input = this.coder.inputOf(id);
      if (input) commands.push({ playerId: id, input: this.recordForm(input) });
    }
    const messages = this.sim.playerIds().includes(this.playerId) ? this.ownMessages.forTick(tick) : [];
    return messages.length > 0 ? { tick, leaves: [], joins: [], commands, messages } : { tick, leaves: [], joins: [], commands };
  }

  /** A command as the decoded records give it: game values exactly when the scenario declares fields. */
  private recordForm(c: InputCommand): InputCommand {
    const game = canonicalGame(c.game, this.gameFields);
    const { game: _dropped, ...plain } = c;
    return game === undefined ? plain : { ...plain, game };
  }

  private stepSlot(record: TickInputRecord): void {
    const events = this.window.step(record);
    const state = this.hasState ? this.sim.gameStateValues!() : null;
    this.slots.set(record.tick, { record, events, hash: carriesHash(record.tick) ? this.sim.stateHash() : null, state });
  }

  private confirm(tick: number, slot: Slot, theirs: string | null): void {
    this.slots.delete(tick);
    this.confirmedRecords.set(tick, slot.record);
    this.confirmed = tick + 1;
    this.ownMessages.confirmed(tick, slot.record.messages);
    if (slot.events.length > 0) this.handlers.confirmedEvents(slot.events);
    if (slot.state !== null && (this.lastState === null || !sameState(this.lastState, slot.state))) {
      this.lastState = slot.state;
      this.handlers.confirmedState?.(slot.state);
    }
    if (slot.hash !== null) this.handlers.confirmedHash?.(tick, slot.hash);
    if (theirs === null || slot.hash === null) return;
    if (slot.hash === theirs) this.verified++;
    else this.handlers.desync(tick, slot.hash, theirs);
  }
}
