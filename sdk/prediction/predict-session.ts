// One connection's predicted play: asks the server for predict mode, builds the local simulation from the checkpoint
// (the app's createSimulation), feeds confirmed records to the Predictor, advances it with the own commands the input
// sender fixed (and the own game messages at once), smooths corrections for renderers, hands on the game state of
// confirmed ticks, resyncs on a hash mismatch, measures rollback depth and re-sim time every frame and falls back to
// snapshots when the frame budget stays blown.
import type { ClientMessage } from '../../shared/protocol/client-messages.ts';
import { MAX_INPUT_DELAY_TICKS } from '../../shared/protocol/limits.ts';
import type { CheckpointMessage, RecordMessage } from '../../shared/protocol/predict-messages.ts';
import type { WelcomeMessage } from '../../shared/protocol/server-messages.ts';
import type { GameStateValue } from '../../shared/sim/game-state.ts';
import type { InputCommand } from '../../shared/sim/input.ts';
import type { BodyDescriptor, CharacterState, SimEvent } from '../../shared/sim/types.ts';
import { DEFAULT_MAX_AHEAD_TICKS, Predictor, type PredictSimulation } from './predictor.ts';
import { CorrectionSmoother, type BodyRead } from './smoothing.ts';

/** What createSimulation gets: the room's scenario, resolved parameters and seed. */
export interface PredictSetup {
  scenario: string;
  params: Record<string, number>;
  seed: number | string;
}

/** Options of predicted play (connect(url, { predict })). */
export interface PredictOptions {
  /** Builds the local simulation (Node: Simulation.create with the scenario registry; a page: its physics bundle). */
  createSimulation(setup: PredictSetup): Promise<PredictSimulation>;
  /** Most ticks the prediction runs ahead of the newest confirmed tick. Default 60 (1 s): DEFAULT_MAX_AHEAD_TICKS. */
  maxAheadTicks?: number;
  /**
   * A fast checkpoint every this many ticks (1: every tick). Saving a big world costs more than stepping it; a
   * rollback then re-steps the few confirmed ticks since the checkpoint before the mismatch. Default 4.
   */
  checkpointEveryTicks?: number;
  /** Time one frame may spend re-simulating (ms). Default 1000/60. */
  frameBudgetMs?: number;
  /** Fall back to snapshots after this long with every frame over budget (ms). Default 2000. */
  fallbackAfterMs?: number;
  /** Half-life of correction smoothing (ms; 0: none). Default 80. */
  smoothingHalfLifeMs?: number;
  /**
   * Ticks between an own command and the local tick that applies it (0..MAX_INPUT_DELAY_TICKS): the command is sent
   * for a tick this much later, so it reaches the server earlier relative to its tick and fewer own commands arrive
   * late, at the cost of showing the own move this many ticks later. Default: what the room's welcome announces.
   */
  inputDelayTicks?: number;
}

/** The predicted world for a renderer (copies, smoothed). */
export interface PredictedFrame {
  /** Ticks simulated locally (the own player's newest input is in it). */
  tick: number;
  /** The oldest unconfirmed tick: every tick before it matches the server. */
  confirmedTick: number;
  /** Every body, ids ascending, BODY_STATE_STRIDE floats each (poses with correction offsets applied). */
  bodies: BodyRead;
  /** Present players' characters (feet positions with correction offsets applied). */
  characters: CharacterState[];
}

/** Prediction numbers for a HUD or a net graph. */
export interface PredictionStats {
  /** 'starting' until the checkpoint is in, 'resyncing' after a mismatch, 'snapshot' after a fallback. */
  mode: 'starting' | 'predict' | 'resyncing' | 'snapshot';
  /** Why the client is on snapshots (a budget fallback), else null. */
  reason: string | null;
  /** Ticks between the own input and the local tick that applies it (0: the next local tick). */
  inputDelayTicks: number;
  /** The present local tick and the oldest unconfirmed one. */
  presentTick: number | null;
  confirmedTick: number | null;
  /** Rollback depth (ticks re-simulated) of the last frame, and p50/p99/max over the last 600 frames. */
  rollbackDepth: number;
  rollbackDepthP50: number;
  rollbackDepthP99: number;
  rollbackDepthMax: number;
  /** Time spent simulating in the last frame (ms), and p50/p99 over the last 600 frames. */
  resimMs: number;
  resimMsP50: number;
  resimMsP99: number;
  /** Rollbacks that changed the present world. */
  corrections: number;
  /** Hash mismatches with the server (each triggers a resync). */
  desyncs: number;
  /** Checkpoints applied after the first. */
  resyncs: number;
  /** Server hashes of confirmed ticks that matched the local simulation (one every 30 ticks). */
  hashesVerified: number;
  /** Our state hashes after the last confirmed ticks that carry one (`tick`: the input record's), oldest first. */
  confirmedHashes: Array<{ tick: number; hash: string }>;
  /** Frames advanced. */
  frames: number;
}

/** What a PredictSession needs from its link. */
export interface PredictLink {
  send(m: ClientMessage): void;
  nowMs(): number;
  /** Confirmed events, in tick order. */
  events(events: SimEvent[]): void;
  /** The game state of the newest confirmed tick, in the welcome's field order (when it changed). */
  gameState(values: GameStateValue[]): void;
  /** Something the server sent could not be used. */
  protocolError(message: string): void;
  /** The session fell back to snapshots (the link keeps interpolating them). */
  fellBack(reason: string): void;
}

const HISTORY = 600;
/** Confirmed-tick hashes kept for stats() (one every 30 ticks: 8 s of play). */
const CONFIRMED_HASHES_KEPT = 16;

function percentile(values: readonly number[], p: number): number {
  if (values.length === 0) return 0;
  const sorted = [...values].sort((a, b) => a - b);
  return sorted[Math.min(sorted.length - 1, Math.floor(p * sorted.length))];
}

/** Checks an input delay (the predict option's or a welcome's); throws a clear Error for a bad one. */
export function checkInputDelay(ticks: number): number {
  if (!Number.isInteger(ticks) || ticks < 0 || ticks > MAX_INPUT_DELAY_TICKS) {
    throw new Error(`connect: predict.inputDelayTicks must be an integer in [0, ${MAX_INPUT_DELAY_TICKS}], got ${String(ticks)}`);
  }
  return ticks;
}

/** Predicted play on one connection; built by the link when the welcome says the room predicts. */
export class PredictSession {
  private readonly opts: PredictOptions;
  private readonly link: PredictLink;
  private readonly welcome: WelcomeMessage;
  private readonly smoother: CorrectionSmoother;
  /** Ticks between an own command and the local tick that applies it (the option, else the room's). */
  readonly inputDelayTicks: number;
  private sim: PredictSimulation | null = null;
  private simPromise: Promise<PredictSimulation> | null = null;
  private predictor: Predictor | null = null;
  /** Records that arrived after the latest checkpoint, before it was applied. */
  private pending: RecordMessage[] = [];
  /** The newest checkpoint: only it is applied (an older one still waiting for the simulation is skipped). */
  private latestCheckpoint: CheckpointMessage | null = null;
  private disposed = false;
  private checkpoints = 0;
  private modeValue: PredictionStats['mode'] = 'starting';
  private reason: string | null = null;
  private awaitingCheckpoint = true;
  private readonly depths: number[] = [];
  private readonly resims: number[] = [];
  private lastDepth = 0;
  private lastResimMs = 0;
  private corrections = 0;
  private desyncs = 0;
  private frames = 0;
  private overBudgetSinceMs: number | null = null;
  private resyncSentMs: number | null = null;
  /** Hashes verified by predictors before the last resync. */
  private verifiedBefore = 0;
  private readonly confirmedHashes: Array<{ tick: number; hash: string }> = [];
  private lastFrameMs: number | null = null;

  constructor(welcome: WelcomeMessage, opts: PredictOptions, link: PredictLink) {
    if (typeof opts?.createSimulation !== 'function') throw new Error('connect: predict.createSimulation must be a function');
    this.inputDelayTicks = checkInputDelay(opts.inputDelayTicks ?? welcome.inputDelayTicks);
    this.welcome = welcome;
    this.opts = opts;
    this.link = link;
    this.smoother = new CorrectionSmoother(opts.smoothingHalfLifeMs ?? 80);
    link.send({ type: 'netMode', mode: 'predict' });
  }

  /** Whether the session still predicts (false after a fallback). */
  get active(): boolean {
    return this.modeValue !== 'snapshot';
  }

  /** A checkpoint arrived (the first, or the answer to a resync). */
  onCheckpoint(m: CheckpointMessage): void {
    if (!this.active) return;
    this.awaitingCheckpoint = false;
    this.resyncSentMs = null;
    this.pending = [];
    this.latestCheckpoint = m;
    this.simPromise ??= this.opts.createSimulation({ scenario: this.welcome.scenario.name, params: { ...this.welcome.scenario.params }, seed: m.seed });
    this.simPromise.then(
      (sim) => this.start(sim, m),
      (error: unknown) => this.fallBack(`the local simulation could not be created: ${error instanceof Error ? error.message : String(error)}`),
    );
  }

  /** A confirmed record arrived. */
  onRecord(m: RecordMessage): void {
    if (!this.active || this.awaitingCheckpoint) return;
    if (!this.predictor) {
      this.pending.push(m);
      return;
    }
    try {
      this.predictor.receive(m);
    } catch (error) {
      this.link.protocolError(`record not applied: ${(error as Error).message}`);
      this.resync();
    }
  }

  /**
   * An own game message is being sent: the local simulation applies it on its next predicted tick, which is returned
   * (the tick to ask the server for). Sent while no predictor runs (starting, resyncing), it is only the server's:
   * null, and it shows in the next checkpoint's state.
   */
  onOwnMessage(name: string, payload: readonly number[]): number | null {
    if (!this.active || !this.predictor) return null;
    return this.predictor.sendMessage(name, payload);
  }

  /** One frame: apply confirmed records, predict to `targetTick` (exclusive), measure. */
  advance(targetTick: number, ownCommand: (tick: number) => InputCommand | undefined): void {
    const p = this.predictor;
    const started = this.link.nowMs();
    // A resync the server refused (at most one a second) is asked for again.
    if (this.awaitingCheckpoint && this.resyncSentMs !== null && started - this.resyncSentMs > 1500 && this.active) {
      this.resyncSentMs = started;
      this.link.send({ type: 'resync' });
    }
    if (!p || !this.active) return;
    const before = p.queuedRecords > 0 ? this.smoother.capture(this.sim!.readBodyStates()) : null;
    let report;
    // The world after the rollback, at the tick it was drawn at, against what was drawn: the difference is hidden.
    const corrected = (): void => {
      if (before && this.smoother.correct(before, this.sim!.readBodyStates()) > 0) this.corrections++;
    };
    try {
      report = p.advance(targetTick, ownCommand, corrected);
    } catch (error) {
      this.link.protocolError(`prediction failed: ${(error as Error).message}`);
      this.resync();
      return;
    }
    const now = this.link.nowMs();
    if (this.lastFrameMs !== null) this.smoother.decay(now - this.lastFrameMs);
    this.lastFrameMs = now;
    this.measure(report.rollbackTicks, now - started, now);
  }

  /** The predicted world, smoothed (null until the checkpoint is in). */
  frame(): PredictedFrame | null {
    const sim = this.sim;
    const p = this.predictor;
    if (!sim || !p || !this.active) return null;
    const read = sim.readBodyStates();
    const characters = sim.characters().map((c) => {
      const o = this.smoother.positionOffset(c.bodyId);
      return o ? { ...c, position: { x: c.position.x + o[0], y: c.position.y + o[1], z: c.position.z + o[2] } } : c;
    });
    return { tick: p.presentTick, confirmedTick: p.confirmedTick, bodies: this.smoother.apply(read), characters };
  }

  /** The descriptor of a body in the local simulation. */
  descriptor(id: number): BodyDescriptor | undefined {
    return this.active ? this.sim?.bodyDescriptor(id) : undefined;
  }

  /** Prediction numbers. */
  stats(): PredictionStats {
    return {
      mode: this.modeValue,
      reason: this.reason,
      inputDelayTicks: this.inputDelayTicks,
      presentTick: this.predictor?.presentTick ?? null,
      confirmedTick: this.predictor?.confirmedTick ?? null,
      rollbackDepth: this.lastDepth,
      rollbackDepthP50: percentile(this.depths, 0.5),
      rollbackDepthP99: percentile(this.depths, 0.99),
      rollbackDepthMax: this.depths.length === 0 ? 0 : Math.max(...this.depths),
      resimMs: this.lastResimMs,
      resimMsP50: percentile(this.resims, 0.5),
      resimMsP99: percentile(this.resims, 0.99),
      corrections: this.corrections,
      desyncs: this.desyncs,
      resyncs: Math.max(0, this.checkpoints - 1),
      hashesVerified: this.verifiedBefore + (this.predictor?.hashesVerified ?? 0),
      confirmedHashes: this.confirmedHashes.slice(),
      frames: this.frames,
    };
  }

  /** Frees the local simulation. */
  dispose(): void {
    this.disposed = true;
    this.predictor?.dispose();
    this.predictor = null;
    this.sim?.destroy();
    this.sim = null;
  }

  /** Stops predicting and asks the server for snapshots. */
  fallBack(reason: string): void {
    if (!this.active) return;
    this.modeValue = 'snapshot';
    this.reason = reason;
    this.link.send({ type: 'netMode', mode: 'snapshot' });
    this.dispose();
    this.link.fellBack(reason);
  }

  private start(sim: PredictSimulation, m: CheckpointMessage): void {
    if (!this.active || this.disposed) {
      // The link ended or fell back while the simulation was being built: nobody will use it.
      if (this.sim !== sim) sim.destroy();
      return;
    }
    if (m !== this.latestCheckpoint) return;
    this.sim = sim;
    this.verifiedBefore += this.predictor?.hashesVerified ?? 0;
    this.predictor?.dispose();
    this.predictor = null;
    try {
      sim.restoreCheckpointBytes(m.bytes);
      this.predictor = new Predictor(sim, m, this.welcome.playerId, {
        confirmedEvents: (events) => this.link.events(events),
        confirmedState: (values) => this.link.gameState(values),
        desync: (tick, ours, theirs) => this.onDesync(tick, ours, theirs),
        confirmedHash: (tick, hash) => {
          this.confirmedHashes.push({ tick, hash });
          if (this.confirmedHashes.length > CONFIRMED_HASHES_KEPT) this.confirmedHashes.shift();
        },
      }, this.opts.maxAheadTicks ?? DEFAULT_MAX_AHEAD_TICKS, this.opts.checkpointEveryTicks ?? 4);
      const state = this.predictor.startState();
      if (state !== null) this.link.gameState(state);
    } catch (error) {
      this.fallBack(`the checkpoint could not be restored: ${(error as Error).message}`);
      return;
    }
    this.checkpoints++;
    this.smoother.clear();
    this.modeValue = 'predict';
    const pending = this.pending;
    this.pending = [];
    for (const r of pending) this.onRecord(r);
  }

  private onDesync(tick: number, ours: string, theirs: string): void {
    this.desyncs++;
    this.link.protocolError(`desync at tick ${tick}: local hash ${ours}, server ${theirs}; resyncing`);
    this.resync();
  }

  private resync(): void {
    if (!this.active || this.awaitingCheckpoint) return;
    this.awaitingCheckpoint = true;
    this.modeValue = 'resyncing';
    this.verifiedBefore += this.predictor?.hashesVerified ?? 0;
    this.predictor?.dispose();
    this.predictor = null;
    this.pending = [];
    this.resyncSentMs = this.link.nowMs();
    this.link.send({ type: 'resync' });
  }

  private measure(depth: number, ms: number, now: number): void {
    this.frames++;
    this.lastDepth = depth;
    this.lastResimMs = ms;
    this.depths.push(depth);
    this.resims.push(ms);
    if (this.depths.length > HISTORY) this.depths.shift();
    if (this.resims.length > HISTORY) this.resims.shift();
    const budget = this.opts.frameBudgetMs ?? 1000 / 60;
    if (ms <= budget) {
      this.overBudgetSinceMs = null;
      return;
    }
    this.overBudgetSinceMs ??= now;
    const limit = this.opts.fallbackAfterMs ?? 2000;
    if (now - this.overBudgetSinceMs >= limit) this.fallBack(`every frame for ${Math.round(now - this.overBudgetSinceMs)} ms spent over the ${budget.toFixed(1)} ms budget re-simulating`);
  }
}
