// character-course door: a hidden trigger zone (sensor on the Trigger layer) spanning the doorway; a player entering
// slides the kinematic door open (moveKinematic) and emits ('door', 1); once empty for a while it closes ('door', 0).
import { CollisionLayer } from '../../shared/physics/index.ts';
import type { ScenarioContext } from '../../shared/sim/scenario.ts';
import type { SimEvent } from '../../shared/sim/types.ts';
import { TICK_DT_SECONDS } from '../../shared/tick-rate.ts';
import { Palette } from '../lib/palette.ts';
import { DOORWAY, WALL } from './layout.ts';

const DOOR_HALF = { x: 0.15, y: DOORWAY.height / 2, z: (DOORWAY.maxZ - DOORWAY.minZ) / 2 };
/** How far the door slides (towards -z, into the wall) when open (m). */
export const DOOR_TRAVEL_METRES = DOORWAY.maxZ - DOORWAY.minZ + 0.1;
/** Door speed (m/s). */
const DOOR_SPEED_METRES_PER_SECOND = 3;

/** The door's closed centre. */
export const DOOR_CLOSED = { x: WALL.x, y: DOORWAY.height / 2, z: (DOORWAY.minZ + DOORWAY.maxZ) / 2 } as const;
/** The trigger zone: both sides of the doorway, where a player walking up to the door stands. */
export const TRIGGER_ZONE = { min: { x: WALL.x - 3, y: 0, z: DOORWAY.minZ - 0.5 }, max: { x: WALL.x + 3, y: 2.5, z: DOORWAY.maxZ + 0.5 } } as const;

/** The door and its trigger, with the state checkpoints must carry. */
export class SlidingDoor {
  readonly doorId: number;
  readonly triggerId: number;
  private readonly closeDelayTicks: number;
  /** 1 while open (or opening), 0 while closed (or closing). */
  private open = 0;
  /** How far the door has slid (m), 0 closed … DOOR_TRAVEL_METRES open. */
  private offsetMetres = 0;
  /** Ids of character bodies inside the trigger, ascending. */
  private occupants: number[] = [];
  /** The last tick someone was inside. */
  private lastOccupiedTick = -1;

  constructor(ctx: ScenarioContext, closeDelayTicks: number) {
    this.closeDelayTicks = closeDelayTicks;
    const z = TRIGGER_ZONE;
    const half = { x: (z.max.x - z.min.x) / 2, y: (z.max.y - z.min.y) / 2, z: (z.max.z - z.min.z) / 2 };
    const centre = { x: (z.max.x + z.min.x) / 2, y: (z.max.y + z.min.y) / 2, z: (z.max.z + z.min.z) / 2 };
    this.triggerId = ctx.spawn({ kind: 'box', halfExtents: half }, centre, null, {
      motion: 'static',
      isSensor: true,
      layer: CollisionLayer.Trigger,
      mask: CollisionLayer.Player,
      color: Palette.trigger,
      hidden: true,
      name: 'door trigger',
    }).id;
    this.doorId = ctx.spawn({ kind: 'box', halfExtents: DOOR_HALF }, DOOR_CLOSED, null, {
      motion: 'kinematic',
      friction: 0.5,
      color: Palette.door,
      name: 'door',
    }).id;
  }

  /** Whether the door is open or opening. */
  get isOpen(): boolean {
    return this.open === 1;
  }

  /** How far the door has slid (m). */
  get offset(): number {
    return this.offsetMetres;
  }

  /** Tracks players entering and leaving the trigger; opens the door on the first one in. */
  onEvents(ctx: ScenarioContext, events: readonly SimEvent[]): void {
    for (const e of events) {
      if ((e.type !== 'sensorEnter' && e.type !== 'sensorExit') || e.sensorId !== this.triggerId || e.playerId === undefined) continue;
      const i = this.occupants.indexOf(e.bodyId);
      if (e.type === 'sensorEnter' && i < 0) this.occupants = [...this.occupants, e.bodyId].sort((a, b) => a - b);
      if (e.type === 'sensorExit' && i >= 0) this.occupants = this.occupants.filter((id) => id !== e.bodyId);
    }
    if (this.occupants.length > 0) {
      this.lastOccupiedTick = ctx.tick;
      if (this.open === 0) {
        this.open = 1;
        ctx.emit('door', 1);
      }
    }
  }

  /** Closes the door after the delay and slides it one tick towards where it should be. */
  onTick(ctx: ScenarioContext): void {
    // A player who left the session inside the zone takes their body with them: forget it.
    this.occupants = this.occupants.filter((id) => ctx.world.getBody(id) !== undefined);
    if (this.occupants.length > 0) this.lastOccupiedTick = ctx.tick;
    if (this.open === 1 && this.occupants.length === 0 && ctx.tick - this.lastOccupiedTick >= this.closeDelayTicks) {
      this.open = 0;
      ctx.emit('door', 0);
    }
    const goal = this.open === 1 ? DOOR_TRAVEL_METRES : 0;
    const stepMetres = DOOR_SPEED_METRES_PER_SECOND * TICK_DT_SECONDS;
    const next = this.offsetMetres < goal ? Math.min(goal, this.offsetMetres + stepMetres) : Math.max(goal, this.offsetMetres - stepMetres);
    if (next !== this.offsetMetres || ctx.world.getBody(this.doorId)!.isActive()) {
      // moveKinematic sets the velocity that reaches the goal in one step, so the door pushes what is in its way.
      ctx.world.moveKinematic(this.doorId, { x: DOOR_CLOSED.x, y: DOOR_CLOSED.y, z: DOOR_CLOSED.z - next }, null, TICK_DT_SECONDS);
    }
    this.offsetMetres = next;
  }

  /** [open, offset, lastOccupiedTick, occupant count, ...occupant ids]. */
  save(): number[] {
    return [this.open, this.offsetMetres, this.lastOccupiedTick, this.occupants.length, ...this.occupants];
  }

  /** Restores what save() wrote, starting at `state[at]`; returns the index after it. */
  restore(state: readonly number[], at: number): number {
    const n = state[at + 3];
    if (!(state[at] === 0 || state[at] === 1) || !Number.isInteger(n) || n < 0 || at + 4 + n > state.length) {
      throw new Error('character-course: bad saved door state');
    }
    this.open = state[at];
    this.offsetMetres = state[at + 1];
    this.lastOccupiedTick = state[at + 2];
    this.occupants = state.slice(at + 4, at + 4 + n);
    return at + 4 + n;
  }
}
