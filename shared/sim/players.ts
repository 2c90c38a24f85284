// The player table: one CharacterController per present player, the command each player last applied (repeated on
// ticks without a new one), fire cooldowns, and how commands turn into walking, jumping and fire requests.
import { CharacterController, CollisionLayer, type CharacterOptions, type PhysicsWorld, type ShapeSpec, type Vec3Like } from '../physics/index.ts';
import { recreateCharacter } from '../physics/internal.ts';
import { aimDirection, commandPitchRadians, commandYawRadians, walkVelocity } from './controls.ts';
import { Button, NEUTRAL_INPUT, type InputCommand } from './input.ts';
import type { PlayerRules } from './scenario.ts';
import type { CharacterState } from './types.ts';

/** Capsule size of every player character (m): 1.9 m tall. */
export const CHARACTER_RADIUS_METRES = 0.35;
export const CHARACTER_HALF_HEIGHT_METRES = 0.6;
/** Eye height above the feet (m), where bullets start from. */
export const EYE_HEIGHT_METRES = 1.7;

/** How a client draws a character: the capsule standing on the body origin (the feet). */
export const CHARACTER_SHAPE = Object.freeze({
  kind: 'compound',
  parts: [
    {
      shape: { kind: 'capsule', halfHeight: CHARACTER_HALF_HEIGHT_METRES, radius: CHARACTER_RADIUS_METRES },
      position: { x: 0, y: CHARACTER_HALF_HEIGHT_METRES + CHARACTER_RADIUS_METRES, z: 0 },
    },
  ],
}) as ShapeSpec;

/** Player cap of a scenario that declares none (players.maxPlayers). */
export const DEFAULT_MAX_PLAYERS = 64;
/** Highest player cap a scenario may declare. */
export const MAX_PLAYERS_LIMIT = 4096;

/** Player rules with every default filled in. */
export interface ResolvedPlayerRules {
  walkSpeedMetresPerSecond: number;
  jumpSpeedMetresPerSecond: number;
  bulletsHitPlayers: boolean;
  fireCooldownTicks: number;
  bulletLifetimeTicks: number;
  bulletSpeedMetresPerSecond: number;
  maxPlayers: number;
  stepUpHeightMetres: number;
  stickToFloorMetres: number;
}

/** Fills and checks a scenario's player rules. */
export function resolvePlayerRules(rules: PlayerRules = {}, scenarioName = 'scenario'): ResolvedPlayerRules {
  const num = (v: number | undefined, fallback: number, min: number, max: number, field: string, integer = false): number => {
    const value = v ?? fallback;
    if (typeof value !== 'number' || !Number.isFinite(value) || value < min || value > max || (integer && !Number.isInteger(value))) {
      throw new Error(`${scenarioName}: players.${field} must be ${integer ? 'an integer' : 'a number'} in [${min}, ${max}], got ${String(value)}`);
    }
    return value;
  };
  return {
    walkSpeedMetresPerSecond: num(rules.walkSpeedMetresPerSecond, 4, 0, 100, 'walkSpeedMetresPerSecond'),
    jumpSpeedMetresPerSecond: num(rules.jumpSpeedMetresPerSecond, 5, 0.1, 100, 'jumpSpeedMetresPerSecond'),
    bulletsHitPlayers: rules.bulletsHitPlayers === true,
    fireCooldownTicks: num(rules.fireCooldownTicks, 10, 1, 3600, 'fireCooldownTicks', true),
    bulletLifetimeTicks: num(rules.bulletLifetimeTicks, 120, 1, 36000, 'bulletLifetimeTicks', true),
    bulletSpeedMetresPerSecond: num(rules.bulletSpeedMetresPerSecond, 40, 1, 1000, 'bulletSpeedMetresPerSecond'),
    maxPlayers: num(rules.maxPlayers, DEFAULT_MAX_PLAYERS, 1, MAX_PLAYERS_LIMIT, 'maxPlayers', true),
    stepUpHeightMetres: num(rules.stepUpHeightMetres, 0.4, 0, 10, 'stepUpHeightMetres'),
    stickToFloorMetres: num(rules.stickToFloorMetres, 0.5, 0, 10, 'stickToFloorMetres'),
  };
}

/** One present player. The controller is live Jolt state; the rest is plain data. */
export interface Player {
  readonly playerId: number;
  readonly name: string;
  /** Counts every join of the session from 0: picks the spawn point, colour and no-collide group. */
  readonly joinIndex: number;
  readonly controller: CharacterController;
  readonly bodyId: number;
  /** The last command applied (repeated while no new one arrives). */
  input: InputCommand;
  /** First tick at which this player may fire again. */
  nextFireTick: number;
}

/** Plain-data form of a player (checkpoints, hash). */
export interface PlayerSnapshot {
  playerId: number;
  name: string;
  joinIndex: number;
  bodyId: number;
  joltId: number;
  input: InputCommand;
  nextFireTick: number;
}

/** The scenario rules a character is built with. */
export type CharacterRules = Pick<ResolvedPlayerRules, 'stepUpHeightMetres' | 'stickToFloorMetres'>;

/** Creates the character of a joining player at `feet`; `restoreIds` recreates a saved one exactly. */
export function createCharacter(world: PhysicsWorld, rules: CharacterRules, playerId: number, joinIndex: number, feet: Vec3Like, restoreIds?: { id: number; joltId: number }): CharacterController {
  const opts: CharacterOptions = {
    stepUpHeight: rules.stepUpHeightMetres,
    stickToFloorDistance: rules.stickToFloorMetres,
    position: feet,
    radius: CHARACTER_RADIUS_METRES,
    halfHeight: CHARACTER_HALF_HEIGHT_METRES,
    layer: CollisionLayer.Player,
    mask: CollisionLayer.All,
    noCollideGroup: joinIndex,
    name: `player ${playerId}`,
  };
  return restoreIds ? recreateCharacter(world, opts, restoreIds) : new CharacterController(world, opts);
}

/** Present players by id; iteration helpers always go in ascending id order. */
export class PlayerTable {
  private readonly players = new Map<number, Player>();
  private sorted: Player[] = [];
  /** Joins so far (the next join's joinIndex). */
  joinCount = 0;

  has(playerId: number): boolean {
    return this.players.has(playerId);
  }

  get(playerId: number): Player | undefined {
    return this.players.get(playerId);
  }

  get size(): number {
    return this.players.size;
  }

  /** Present players, ascending id (do not mutate the array). */
  inOrder(): readonly Player[] {
    return this.sorted;
  }

  /** Adds a player whose character exists. */
  add(player: Player): void {
    if (this.players.has(player.playerId)) throw new Error(`player ${player.playerId} is already present`);
    this.players.set(player.playerId, player);
    // Insert in id order (a crowd joining in one tick must not re-sort the table once per join).
    let lo = 0;
    let hi = this.sorted.length;
    while (lo < hi) {
      const mid = (lo + hi) >> 1;
      if (this.sorted[mid].playerId < player.playerId) lo = mid + 1;
      else hi = mid;
    }
    this.sorted = [...this.sorted.slice(0, lo), player, ...this.sorted.slice(lo)];
  }

  /** Removes a player and destroys its character. */
  remove(playerId: number): Player {
    const p = this.players.get(playerId);
    if (!p) throw new Error(`no player ${playerId}`);
    p.controller.destroy();
    this.players.delete(playerId);
    this.sorted = this.sorted.filter((q) => q !== p);
    return p;
  }

  /** Plain snapshots, ascending id. */
  snapshot(): PlayerSnapshot[] {
    return this.sorted.map((p) => ({
      playerId: p.playerId,
      name: p.name,
      joinIndex: p.joinIndex,
      bodyId: p.bodyId,
      joltId: p.controller.body!.joltId,
      input: { ...p.input },
      nextFireTick: p.nextFireTick,
    }));
  }

  /** Character views for other layers, ascending player id. */
  characterStates(): CharacterState[] {
    return this.sorted.map((p) => {
      const c = p.controller;
      return {
        playerId: p.playerId,
        bodyId: p.bodyId,
        position: c.position,
        velocity: { x: c.velocity.x, y: c.velocity.y, z: c.velocity.z },
        yaw: commandYawRadians(p.input),
        pitch: commandPitchRadians(p.input),
        groundState: c.groundState,
        buttons: p.input.buttons,
      };
    });
  }
}

/** A new player record for a fresh join. */
export function newPlayer(playerId: number, name: string, joinIndex: number, controller: CharacterController): Player {
  return { playerId, name, joinIndex, controller, bodyId: controller.body!.id, input: { ...NEUTRAL_INPUT }, nextFireTick: 0 };
}

/** Where applyCommand reads the ground's velocity (plain numbers, used at once). */
const groundScratch: Vec3Like = { x: 0, y: 0, z: 0 };

/**
 * Applies a command to a player's character: horizontal velocity from the move axes (plus the ground's velocity
 * when standing on walkable ground), a jump when Jump is held on walkable ground. Returns the aim direction when the player fires this tick (Fire held, cooldown over), else null.
 */
export function applyCommand(p: Player, cmd: InputCommand, rules: ResolvedPlayerRules, tick: number): Vec3Like | null {
  p.input = cmd;
  const c = p.controller;
  const v = walkVelocity(cmd, rules.walkSpeedMetresPerSecond, (cmd.buttons & Button.Sprint) !== 0);
  // On walkable ground the character also rides what it stands on (moving platforms, drifting crates).
  const grounded = c.isGrounded;
  const ground = grounded ? c.groundVelocityInto(groundScratch) : null;
  c.velocity.x = ground ? v.x + ground.x : v.x;
  c.velocity.z = ground ? v.z + ground.z : v.z;
  if ((cmd.buttons & Button.Jump) !== 0 && grounded && !c.jumpPending) c.jump(rules.jumpSpeedMetresPerSecond);
  if ((cmd.buttons & Button.Fire) !== 0 && tick >= p.nextFireTick) {
    p.nextFireTick = tick + rules.fireCooldownTicks;
    return aimDirection(cmd);
  }
  return null;
}
