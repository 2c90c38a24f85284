// Rollback over a Simulation: a fast checkpoint before each stepped tick (or every `everyTicks` ticks, where saving
// costs more than stepping), the last `capacity` of them kept, so the world can return to the start of a recent tick
// and re-simulate from there. Pure and engine-free at run time
// (the simulation is handed in), so the client library can use it around the same Simulation the server runs.
import type { Checkpoint } from './checkpoint.ts';
import type { SimEvent, TickInputRecord } from './types.ts';

/** The part of Simulation a rollback window drives (shared/sim/simulation.ts satisfies it). */
export interface RollbackSimulation {
  readonly tick: number;
  step(record: TickInputRecord): SimEvent[];
  saveCheckpoint(): Checkpoint;
  restoreCheckpoint(cp: Checkpoint): void;
}

/** Fast checkpoints of the last ticks of one simulation; owns them (dispose() frees them all). */
export class RollbackWindow {
  readonly capacity: number;
  /** A checkpoint is saved before ticks that are multiples of this (and whenever the window is empty). */
  readonly everyTicks: number;
  private readonly sim: RollbackSimulation;
  /** Checkpoints by the tick they return to (the state before that tick's record), ascending. */
  private readonly saved = new Map<number, Checkpoint>();

  constructor(sim: RollbackSimulation, capacity: number, everyTicks = 1) {
    if (!Number.isInteger(capacity) || capacity < 1 || capacity > 1024) throw new Error(`RollbackWindow: capacity must be an integer in [1, 1024], got ${String(capacity)}`);
    if (!Number.isInteger(everyTicks) || everyTicks < 1 || everyTicks > 256) throw new Error(`RollbackWindow: everyTicks must be an integer in [1, 256], got ${String(everyTicks)}`);
    this.sim = sim;
    this.capacity = capacity;
    this.everyTicks = everyTicks;
  }

  /** The oldest tick the window can return to, or null when it holds nothing. */
  get oldestTick(): number | null {
    for (const t of this.saved.keys()) return t;
    return null;
  }

  /** How many checkpoints it holds. */
  get size(): number {
    return this.saved.size;
  }

  /** Whether the window can return to the start of `tick`. */
  canRestore(tick: number): boolean {
    return this.saved.has(tick);
  }

  /** The latest tick at or before `tick` the window can return to, or null. */
  latestAtOrBefore(tick: number): number | null {
    let best: number | null = null;
    for (const t of this.saved.keys()) {
      if (t > tick) break;
      best = t;
    }
    return best;
  }

  /** Checkpoints the current state when due (and not already), then steps `record`; the oldest beyond capacity goes. */
  step(record: TickInputRecord): SimEvent[] {
    const tick = this.sim.tick;
    if (!this.saved.has(tick) && (this.saved.size === 0 || tick % this.everyTicks === 0)) this.saved.set(tick, this.sim.saveCheckpoint());
    this.trim();
    return this.sim.step(record);
  }

  /** Returns the simulation to the start of `tick` (a tick the window holds); later checkpoints are dropped. */
  restore(tick: number): void {
    const cp = this.saved.get(tick);
    if (!cp) throw new Error(`RollbackWindow: no checkpoint for tick ${tick} (holding ${this.describe()})`);
    this.sim.restoreCheckpoint(cp);
    for (const [t, c] of this.saved) {
      if (t <= tick) continue;
      c.dispose();
      this.saved.delete(t);
    }
  }

  /** Drops checkpoints of ticks before `tick` (they can no longer be needed). */
  forgetBefore(tick: number): void {
    for (const [t, c] of this.saved) {
      if (t >= tick) break;
      c.dispose();
      this.saved.delete(t);
    }
  }

  /** Frees every checkpoint. */
  dispose(): void {
    for (const c of this.saved.values()) c.dispose();
    this.saved.clear();
  }

  private trim(): void {
    while (this.saved.size > this.capacity) {
      const [t, c] = this.saved.entries().next().value as [number, Checkpoint];
      c.dispose();
      this.saved.delete(t);
    }
  }

  private describe(): string {
    const oldest = this.oldestTick;
    return oldest === null ? 'none' : `ticks ${oldest}..${oldest + this.saved.size - 1}`;
  }
}
