// Input sending: InputSender fixes one command per tick as the target tick advances and builds input messages that
// repeat the last few commands (redundancy); AckCarrier puts snapshot acks on those messages; InputLead picks how many
// ticks ahead of the server to aim, from RTT jitter plus a boost whenever the server reports ticks where our input
// arrived too late.
import type { InputMessage } from '../shared/protocol/client-messages.ts';
import { DEFAULT_INPUT_REDUNDANCY, MAX_INPUT_COMMANDS_PER_MESSAGE } from '../shared/protocol/limits.ts';
import { NEUTRAL_INPUT, validateInputCommand, type InputCommand } from '../shared/sim/input.ts';

/** Options of InputSender. */
export interface InputSenderOptions {
  /** Commands per message: the newest plus this many − 1 repeats. 1..16, default 4. */
  redundancy?: number;
}

/**
 * Keeps the command of each tick once chosen (a repeat always carries the same command) and produces the message for
 * the ticks up to a target. Ticks are only ever generated forwards; a target that moves back sends nothing.
 */
export class InputSender {
  readonly redundancy: number;
  private current: InputCommand = { ...NEUTRAL_INPUT };
  private readonly byTick = new Map<number, InputCommand>();
  private firstTick = -1;
  private lastTick = -1;
  private sentMessages = 0;

  constructor(opts: InputSenderOptions = {}) {
    const r = opts.redundancy ?? DEFAULT_INPUT_REDUNDANCY;
    if (!Number.isInteger(r) || r < 1 || r > MAX_INPUT_COMMANDS_PER_MESSAGE) {
      throw new Error(`InputSender: redundancy must be an integer in [1, ${MAX_INPUT_COMMANDS_PER_MESSAGE}], got ${String(opts.redundancy)}`);
    }
    this.redundancy = r;
  }

  /** Sets the command for ticks generated from now on; throws a clear Error for an invalid command. */
  setCommand(cmd: InputCommand): void {
    const v = validateInputCommand(cmd);
    if (!v.ok) throw new Error(`setInput: ${v.error}`);
    this.current = v.command;
  }

  /** The command new ticks get. */
  get command(): InputCommand {
    return this.current;
  }

  /** The newest tick a command was generated for (−1 before any). */
  get newestTick(): number {
    return this.lastTick;
  }

  /** Messages produced so far. */
  get messageCount(): number {
    return this.sentMessages;
  }

  /** The command generated for a tick, if still remembered. */
  commandFor(tick: number): InputCommand | undefined {
    return this.byTick.get(tick);
  }

  /**
   * Generates commands for every tick after the newest one up to `targetTick` (at most 16: older ones in a long
   * jump are skipped, the server repeats for them) and returns the message carrying them plus repeats; null when the
   * target has not advanced.
   */
  update(targetTick: number): InputMessage | null {
    if (!Number.isInteger(targetTick) || targetTick < 0) throw new Error(`InputSender.update: targetTick must be an integer ≥ 0, got ${targetTick}`);
    if (targetTick <= this.lastTick) return null;
    // The first tick ever starts the run; a jump of more than 16 ticks restarts it (the server repeats meanwhile).
    const from = this.lastTick < 0 ? targetTick : Math.max(this.lastTick + 1, targetTick - MAX_INPUT_COMMANDS_PER_MESSAGE + 1);
    for (let t = from; t <= targetTick; t++) this.byTick.set(t, this.current);
    if (this.lastTick < 0 || from > this.lastTick + 1) this.firstTick = from;
    const newCount = targetTick - from + 1;
    this.lastTick = targetTick;
    const count = Math.min(MAX_INPUT_COMMANDS_PER_MESSAGE, Math.max(this.redundancy, newCount), targetTick - this.firstTick + 1);
    const first = targetTick - count + 1;
    for (const t of this.byTick.keys()) if (t < targetTick - MAX_INPUT_COMMANDS_PER_MESSAGE) this.byTick.delete(t);
    const commands: InputCommand[] = [];
    for (let t = first; t <= targetTick; t++) commands.push(this.byTick.get(t)!);
    this.sentMessages++;
    return { type: 'input', firstTick: first, commands };
  }

  /** Forgets every generated tick (a new connection starts over); the current command stays. */
  reset(): void {
    this.byTick.clear();
    this.firstTick = -1;
    this.lastTick = -1;
  }
}

/** Input pumps an ack may wait for an input message to ride on before it goes out alone (two pumps: one tick). */
export const ACK_WAIT_PUMPS = 2;

/**
 * The snapshot ack that rides on the next input message (protocol 7), so a playing client sends one message per tick,
 * not one per tick plus one per snapshot. Only the newest decoded tick is acked: the server's delta baseline is the
 * newest acked snapshot, and an older ack adds nothing to it. An ack that finds no input message for ACK_WAIT_PUMPS
 * pumps (a client that sends no input, or a stalled target) goes out alone as an `ack` message.
 */
export class AckCarrier {
  private pending: number | null = null;
  private waitedPumps = 0;

  /** The snapshot of `tick` was decoded and kept. */
  decoded(tick: number): void {
    if (this.pending === null || tick > this.pending) this.pending = tick;
  }

  /** The tick to carry on the input message going out now (then forgotten), or undefined when there is none. */
  carry(): number | undefined {
    const tick = this.pending;
    this.pending = null;
    this.waitedPumps = 0;
    return tick ?? undefined;
  }

  /** A pump sent no input message: the tick to ack alone now (then forgotten), or null while it may still wait. */
  alone(): number | null {
    if (this.pending === null) return null;
    if (++this.waitedPumps < ACK_WAIT_PUMPS) return null;
    return this.carry() ?? null;
  }
}

/** Options of InputLead. */
export interface InputLeadOptions {
  tickRateHz: number;
  /** Fewest ticks of lead (a fraction of a tick is fine). Default 0. */
  minLeadTicks?: number;
  /** Most ticks of lead. Default 12. */
  maxLeadTicks?: number;
  /** Safety margin added to twice the RTT jitter (ms). Default 4. */
  marginMs?: number;
  /** A boost from late inputs decays by one step after this long without new misses (ms). Default 8000. */
  decayMs?: number;
  /** How much lead (ticks) each report of late inputs adds, and each quiet period removes. Default 0.25. */
  boostStepTicks?: number;
}

/**
 * The adaptive input lead, in (fractional) ticks: (2·jitter + margin) / tick + boost, clamped; boost rises by a
 * quarter tick each time the server reports late inputs. The sender targets floor(estimated server tick at arrival + lead):
 * the earliest tick that still leaves the margin, so on a calm link an input is applied by the first tick after it
 * arrives.
 */
export class InputLead {
  private readonly tickMs: number;
  private readonly minLead: number;
  private readonly maxLead: number;
  private readonly marginMs: number;
  private readonly decayMs: number;
  private boost = 0;
  private readonly boostStep: number;
  private lastMissed: number | null = null;
  private lastChangeMs = 0;
  private lead: number;

  constructor(opts: InputLeadOptions) {
    this.tickMs = 1000 / opts.tickRateHz;
    this.minLead = opts.minLeadTicks ?? 0;
    this.maxLead = opts.maxLeadTicks ?? 12;
    this.marginMs = opts.marginMs ?? 4;
    this.decayMs = opts.decayMs ?? 8000;
    this.boostStep = opts.boostStepTicks ?? 0.25;
    if (!(this.boostStep > 0 && this.boostStep <= 12)) throw new Error('InputLead: boostStepTicks must be in (0, 12]');
    if (!(this.minLead >= 0 && this.maxLead >= this.minLead)) throw new Error('InputLead: need 0 ≤ minLeadTicks ≤ maxLeadTicks');
    this.lead = this.minLead;
  }

  /** Current lead in (fractional) ticks. */
  get leadTicks(): number {
    return this.lead;
  }

  /** Extra ticks added because the server reported late inputs. */
  get boostTicks(): number {
    return this.boost;
  }

  /** Recomputes the lead from the RTT jitter and the server's cumulative missed-input count (from the last pong). */
  update(jitterMs: number, missedInputTicks: number | null, nowMs: number): number {
    if (missedInputTicks !== null) {
      if (this.lastMissed !== null && missedInputTicks > this.lastMissed) {
        this.boost = Math.min(this.boost + this.boostStep, this.maxLead);
        this.lastChangeMs = nowMs;
      }
      this.lastMissed = missedInputTicks;
    }
    if (this.boost > 0 && nowMs - this.lastChangeMs >= this.decayMs) {
      this.boost = Math.max(0, this.boost - this.boostStep);
      this.lastChangeMs = nowMs;
    }
    const base = (2 * Math.max(0, jitterMs) + this.marginMs) / this.tickMs;
    this.lead = Math.max(this.minLead, Math.min(this.maxLead, base + this.boost));
    return this.lead;
  }

  /** Starts over (a new connection). */
  reset(): void {
    this.boost = 0;
    this.lastMissed = null;
    this.lead = this.minLead;
  }
}
