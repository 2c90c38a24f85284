// Scripted bots: seeded players that join at given ticks and then walk, turn, sprint, jump and fire in bursts. They
// produce the exact TickInputRecords of golden runs, `record --bots N` and the benchmarks (own PRNG, not the sim's).
import { Button, MOVE_STEPS, PITCH_STEPS, YAW_STEPS, type InputCommand } from './input.ts';
import { Prng } from './prng.ts';
import type { PlayerCommand, PlayerJoin, TickInputRecord } from './types.ts';

/** Options of a BotScript. */
export interface BotScriptOptions {
  /** Seed of the bots' own PRNG. */
  seed: number | string;
  /** How many bots. */
  bots: number;
  /** Player id of the first bot; the others follow consecutively. Default 1. */
  firstPlayerId?: number;
  /** Tick each bot joins at (length = bots); default bot i joins at i · joinSpacingTicks. */
  joinTicks?: readonly number[];
  /** Ticks between two default joins. Default 10. */
  joinSpacingTicks?: number;
  /** Tick each bot leaves at (omit or -1: never). */
  leaveTicks?: readonly number[];
  /** Whether bots shoot. Default true. */
  fire?: boolean;
}

type Mode = 'walk' | 'strafe' | 'idle';

interface Bot {
  playerId: number;
  joinTick: number;
  leaveTick: number;
  present: boolean;
  yaw: number;
  turnPerTick: number;
  pitch: number;
  mode: Mode;
  modeTicks: number;
  sprint: boolean;
  strafeDir: number;
  burstTicks: number;
}

function tickList(values: readonly number[] | undefined, n: number, fallback: (i: number) => number, what: string): number[] {
  if (values === undefined) return Array.from({ length: n }, (_, i) => fallback(i));
  if (!Array.isArray(values) || values.length !== n) throw new Error(`BotScript: ${what} must list one tick per bot (${n})`);
  return values.map((t) => {
    if (!Number.isInteger(t) || t < -1) throw new Error(`BotScript: ${what} must be integers >= 0 (or -1), got ${String(t)}`);
    return t;
  });
}

/** Produces one TickInputRecord per tick, in order from tick 0, for a deterministic crowd of bots. */
export class BotScript {
  private readonly rng: Prng;
  private readonly bots: Bot[];
  private readonly fire: boolean;
  private nextTick = 0;

  constructor(opts: BotScriptOptions) {
    const n = opts.bots;
    if (!Number.isInteger(n) || n < 0 || n > 10000) throw new Error(`BotScript: bots must be an integer in [0, 10000], got ${String(n)}`);
    const first = opts.firstPlayerId ?? 1;
    if (!Number.isInteger(first) || first < 0 || first + n - 1 > 0xffffffff) throw new Error(`BotScript: firstPlayerId out of range: ${String(first)}`);
    const spacing = opts.joinSpacingTicks ?? 10;
    if (!Number.isInteger(spacing) || spacing < 0) throw new Error(`BotScript: joinSpacingTicks must be an integer >= 0, got ${String(spacing)}`);
    const joins = tickList(opts.joinTicks, n, (i) => i * spacing, 'joinTicks');
    const leaves = tickList(opts.leaveTicks, n, () => -1, 'leaveTicks');
    this.rng = new Prng(opts.seed);
    this.fire = opts.fire !== false;
    this.bots = joins.map((joinTick, i) => {
      if (joinTick < 0) throw new Error(`BotScript: bot ${i} needs a join tick >= 0`);
      if (leaves[i] >= 0 && leaves[i] <= joinTick) throw new Error(`BotScript: bot ${i} leaves (tick ${leaves[i]}) before it joins (tick ${joinTick})`);
      return {
        playerId: first + i,
        joinTick,
        leaveTick: leaves[i],
        present: false,
        yaw: this.rng.int(0, YAW_STEPS - 1),
        turnPerTick: 0,
        pitch: 0,
        mode: 'idle' as Mode,
        modeTicks: 0,
        sprint: false,
        strafeDir: 1,
        burstTicks: 0,
      };
    });
  }

  /** The tick the next record is for. */
  get tick(): number {
    return this.nextTick;
  }

  private chooseMode(b: Bot): void {
    const r = this.rng.next();
    b.mode = r < 0.6 ? 'walk' : r < 0.8 ? 'strafe' : 'idle';
    b.modeTicks = this.rng.int(20, 90);
    b.sprint = this.rng.next() < 0.3;
    b.strafeDir = this.rng.next() < 0.5 ? -1 : 1;
    b.yaw = (b.yaw + this.rng.int(-12000, 12000) + YAW_STEPS) % YAW_STEPS;
    b.turnPerTick = this.rng.int(-250, 250);
    b.pitch = this.rng.int(-PITCH_STEPS / 8, PITCH_STEPS / 4);
  }

  private command(b: Bot): InputCommand {
    if (b.modeTicks <= 0) this.chooseMode(b);
    b.modeTicks--;
    b.yaw = (b.yaw + b.turnPerTick + YAW_STEPS) % YAW_STEPS;
    let buttons = 0;
    let moveX = 0;
    let moveZ = 0;
    if (b.mode === 'walk') moveZ = MOVE_STEPS;
    else if (b.mode === 'strafe') {
      moveX = b.strafeDir * MOVE_STEPS;
      moveZ = 64;
    }
    if (b.sprint && b.mode !== 'idle') buttons |= Button.Sprint;
    if (this.rng.next() < 0.015) buttons |= Button.Jump;
    if (this.fire) {
      if (b.burstTicks <= 0 && this.rng.next() < 0.04) b.burstTicks = this.rng.int(3, 10);
      if (b.burstTicks > 0) {
        b.burstTicks--;
        buttons |= Button.Fire;
      }
    }
    return { moveX, moveZ, yaw: b.yaw, pitch: b.pitch, buttons };
  }

  /** The record for the next tick (tick 0 first). */
  next(): TickInputRecord {
    const tick = this.nextTick++;
    const leaves: number[] = [];
    const joins: PlayerJoin[] = [];
    const commands: PlayerCommand[] = [];
    for (const b of this.bots) {
      if (b.present && b.leaveTick === tick) {
        b.present = false;
        leaves.push(b.playerId);
        continue;
      }
      if (!b.present && b.joinTick === tick) {
        b.present = true;
        joins.push({ playerId: b.playerId, name: `bot-${b.playerId}` });
      }
      if (b.present) commands.push({ playerId: b.playerId, input: this.command(b) });
    }
    return { tick, leaves, joins, commands };
  }

  /** The next `count` records. */
  take(count: number): TickInputRecord[] {
    const out: TickInputRecord[] = [];
    for (let i = 0; i < count; i++) out.push(this.next());
    return out;
  }
}
