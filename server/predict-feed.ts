// A predict-mode room's feed: the record coder every member's stream shares, each tick's record framed once for all
// members (with the state hash on hash ticks), and checkpoint messages for joining and resyncing members.
import { carriesHash, encodeServerMessage, RecordDeltaCoder, type CheckpointMessage } from '../shared/protocol/index.ts';
import type { PlayerInputState } from '../shared/protocol/record-delta.ts';
import type { RecordGameLayout } from '../shared/protocol/record-game-bits.ts';
import type { TickInputRecord } from '../shared/sim/types.ts';

/** What the feed reads from the room's simulation. */
export interface FeedSimulation {
  readonly tick: number;
  stateHash(): string;
  saveCheckpointBytes(): Uint8Array;
}

/** One room's predict-mode feed; the room calls frame() (or skip() when no member takes records) after each step and checkpoint() between ticks. */
export class PredictFeed {
  private readonly coder: RecordDeltaCoder;
  private readonly sim: FeedSimulation;
  private readonly seed: number | string;
  private cachedCheckpoint: { tick: number; message: Uint8Array; sizeBytes: number } | null = null;

  /**
   * `inputs`: the players already in the game and their last commands (a room resumed mid-session); default none.
   * `layout`: the scenario's game input fields and message kinds, which the records carry.
   */
  constructor(sim: FeedSimulation, seed: number | string, inputs: readonly PlayerInputState[] = [], layout?: RecordGameLayout) {
    this.coder = new RecordDeltaCoder(inputs, layout);
    this.sim = sim;
    this.seed = seed;
  }

  /** The room's tick counter: the next record is for this tick. */
  get tick(): number {
    return this.sim.tick;
  }

  /** The record coder's player states after the last record framed (a room moving threads continues the stream). */
  inputs(): PlayerInputState[] {
    return this.coder.state();
  }

  /** The framed record message of the record just stepped (the simulation is now after it). */
  frame(record: TickInputRecord): Uint8Array {
    const { bits, joins } = this.coder.encode(record);
    const hash = carriesHash(record.tick) ? this.sim.stateHash() : null;
    return encodeServerMessage({ type: 'record', tickLow: record.tick & 0xff, bits, joins, hash });
  }

  /** Steps the record coder past a record nobody takes (no member streams records): no bits, no hash, no message. */
  skip(record: TickInputRecord): void {
    this.coder.advance(record);
  }

  /** The framed checkpoint of the room now (between ticks), shared by every member asking within the same tick. */
  checkpoint(): Uint8Array {
    const tick = this.sim.tick;
    if (this.cachedCheckpoint?.tick === tick) return this.cachedCheckpoint.message;
    const message: CheckpointMessage = { type: 'checkpoint', tick, seed: this.seed, bytes: this.sim.saveCheckpointBytes(), inputs: this.coder.state() };
    const framed = encodeServerMessage(message);
    this.cachedCheckpoint = { tick, message: framed, sizeBytes: framed.length };
    return framed;
  }
}
