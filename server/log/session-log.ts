// Records a live Simulation into an input log: header from the simulation's setup, then per tick the input record
// (write-ahead, before it is applied), the step, and the hash / checkpoint records that are due. Used by `record`
// and by any host (the server) that wants its sessions replayable.
import type { Simulation } from '../../shared/sim/simulation.ts';
import { validateTickRecord } from '../../shared/sim/tick-record.ts';
import type { SimEvent, TickInputRecord } from '../../shared/sim/types.ts';
import { TICK_RATE_HZ } from '../../shared/tick-rate.ts';
import { installedJoltVersion } from './jolt-version.ts';
import { LogWriter, type LogWriterOptions } from './log-writer.ts';

/** What to record besides the inputs. */
export interface SessionLogOptions extends LogWriterOptions {
  /** A hash record every K ticks (and one for the initial state); 0: none. Default 1. */
  hashEveryTicks?: number;
  /** A checkpoint record every C ticks; 0: none. Default 600 (every 10 s of play). */
  checkpointEveryTicks?: number;
  /** Names the program in the header. */
  createdBy?: string;
  /** Content hash of the scenario's module (see server/scenario-module.ts); default '' (a built-in scenario). */
  scenarioHash?: string;
}

function interval(value: number | undefined, fallback: number, name: string): number {
  const v = value ?? fallback;
  if (!Number.isInteger(v) || v < 0 || v > 0xffffffff) throw new Error(`SessionLog: ${name} must be an integer ≥ 0, got ${String(v)}`);
  return v;
}

/** A simulation wired to its input log. Create at tick 0, step through it, close() at the end. */
export class SessionLog {
  readonly sim: Simulation;
  readonly writer: LogWriter;
  private readonly hashEvery: number;
  private readonly checkpointEvery: number;

  private constructor(sim: Simulation, writer: LogWriter) {
    this.sim = sim;
    this.writer = writer;
    this.hashEvery = writer.header.hashEveryTicks;
    this.checkpointEvery = writer.header.checkpointEveryTicks;
  }

  /** Creates the log file for a simulation that has not stepped yet and writes the initial hash. */
  static async create(path: string, sim: Simulation, opts: SessionLogOptions = {}): Promise<SessionLog> {
    if (sim.tick !== 0) throw new Error(`SessionLog: the simulation must be at tick 0 (it is at ${sim.tick}); a log always starts with the scene`);
    const hashEveryTicks = interval(opts.hashEveryTicks, 1, 'hashEveryTicks');
    const checkpointEveryTicks = interval(opts.checkpointEveryTicks, 600, 'checkpointEveryTicks');
    const writer = await LogWriter.create(
      path,
      {
        joltVersion: installedJoltVersion(),
        scenario: sim.scenarioName,
        scenarioHash: opts.scenarioHash ?? '',
        params: { ...sim.params },
        seed: sim.seed,
        tickRateHz: TICK_RATE_HZ,
        hashEveryTicks,
        checkpointEveryTicks,
        createdBy: opts.createdBy ?? 'taos-physics',
      },
      opts,
    );
    if (hashEveryTicks > 0) writer.appendHash(0, sim.stateHash());
    return new SessionLog(sim, writer);
  }

  /**
   * Checks the record against the simulation (a record it would reject is never logged: the Error says why and
   * nothing changes), logs it, applies it, then logs the hash and checkpoint due at the new tick.
   */
  step(record: TickInputRecord): SimEvent[] {
    const present = new Set(this.sim.playerIds());
    const clean = validateTickRecord(record, this.sim.tick, (id) => present.has(id));
    this.writer.appendTick(clean);
    const events = this.sim.step(clean);
    const tick = this.sim.tick;
    if (this.hashEvery > 0 && tick % this.hashEvery === 0) this.writer.appendHash(tick, this.sim.stateHash());
    if (this.checkpointEvery > 0 && tick % this.checkpointEvery === 0) this.writer.appendCheckpoint(tick, this.sim.saveCheckpointBytes());
    return events;
  }

  /** Writes the end record (final tick and hash), flushes, fsyncs and closes the file. The simulation stays alive. */
  async close(): Promise<void> {
    await this.writer.close(this.sim.tick, this.sim.stateHash());
  }
}
