// One 60 Hz tick, in the documented order (docs/simulation.md): leaves → joins → game messages (onMessage) → commands (walk, jump, fire) →
// characters move → physics step → scenario onTick → bullet expiry and bounds → sensor events → onEvents.
import { IDENTITY_QUAT, type Vec3Like } from '../physics/index.ts';
import { worldInternals } from '../physics/internal.ts';
import { TICK_DT_SECONDS } from '../tick-rate.ts';
import { makeRecord, playerColor } from './body-registry.ts';
import { BULLET_SHAPE, bulletOptions, muzzlePosition } from './bullets.ts';
import { gameMessageEvent } from './game-messages.ts';
import { applyCommand, CHARACTER_SHAPE, createCharacter, newPlayer, type Player } from './players.ts';
import { assertRegistryInSync, createBody, destroyBody, sensorSimEvents, type SimCore } from './sim-core.ts';
import { validateTickRecord } from './tick-record.ts';
import type { PlayerCommand, PlayerJoin, SimEvent, TickInputRecord } from './types.ts';

function checkSpawnPoint(core: SimCore, joinIndex: number): Vec3Like {
  const p = core.instance.spawnPoint(joinIndex);
  if (!p || !Number.isFinite(p.x) || !Number.isFinite(p.y) || !Number.isFinite(p.z)) {
    throw new Error(`scenario ${core.def.name}: spawnPoint(${joinIndex}) must return finite {x, y, z}`);
  }
  return { x: p.x, y: p.y, z: p.z };
}

function join(core: SimCore, j: PlayerJoin, tick: number): void {
  const joinIndex = core.players.joinCount;
  const feet = checkSpawnPoint(core, joinIndex);
  const controller = createCharacter(core.world, core.rules, j.playerId, joinIndex, feet);
  core.players.joinCount++;
  const player = newPlayer(j.playerId, j.name, joinIndex, controller);
  if (core.gameInputFields.length > 0) player.input = { ...player.input, game: core.gameInputFields.map(() => 0) };
  core.players.add(player);
  core.registry.add(makeRecord('character', controller.body!, CHARACTER_SHAPE, feet, IDENTITY_QUAT, { name: j.name }, { playerId: j.playerId, color: playerColor(joinIndex) }));
  core.tickEvents.push({ type: 'playerJoined', tick, playerId: j.playerId, name: j.name, bodyId: player.bodyId });
}

function leave(core: SimCore, playerId: number, tick: number): void {
  const p = core.players.remove(playerId);
  core.registry.delete(p.bodyId);
  core.departed.set(p.bodyId, playerId);
  core.tickEvents.push({ type: 'playerLeft', tick, playerId });
}

function fire(core: SimCore, p: Player, aim: Vec3Like, tick: number): void {
  // A full world, or a step with no room left for another CCD body, drops the shot. Both limits are per world, so
  // the drop is deterministic (the shared WASM heap is not: running short there fails the tick instead).
  if (core.world.bodyCount >= core.world.maxBodies || core.world.stepBudgetRoom('ccdBody') <= 0) return;
  const r = core.rules;
  const pos = muzzlePosition(p.controller.position, aim);
  const opts = bulletOptions(aim, r.bulletSpeedMetresPerSecond, r.bulletsHitPlayers, p.joinIndex, p.playerId);
  const rec = createBody(core, 'bullet', BULLET_SHAPE, pos, null, opts);
  core.bullets.add({ bodyId: rec.id, ownerId: p.playerId, expireTick: tick + r.bulletLifetimeTicks - 1 });
  core.tickEvents.push({ type: 'bodySpawned', tick, bodyId: rec.id });
}

/** Removes expired bullets and bodies that left the bounds; characters that left are put back at their spawn point. */
function expireAndBound(core: SimCore, tick: number): void {
  for (const b of core.bullets.takeExpired(tick)) {
    if (!core.registry.has(b.bodyId)) continue;
    destroyBody(core, b.bodyId);
    core.tickEvents.push({ type: 'bodyRemoved', tick, bodyId: b.bodyId });
  }
  const { min, max } = core.def.bounds;
  const feet = { x: 0, y: 0, z: 0 };
  for (const id of core.world.awakeBodiesOutside(min, max)) {
    const rec = core.registry.get(id)!;
    if (rec.kind === 'character') continue; // checked below, asleep or not
    if (rec.kind === 'bullet') core.bullets.forget(id);
    destroyBody(core, id);
    core.tickEvents.push({ type: 'bodyRemoved', tick, bodyId: id });
  }
  for (const p of core.players.inOrder()) {
    const { x, y, z } = p.controller.positionInto(feet);
    if (x >= min.x && x <= max.x && y >= min.y && y <= max.y && z >= min.z && z <= max.z) continue;
    p.controller.setPosition(checkSpawnPoint(core, p.joinIndex));
    p.controller.velocity.x = 0;
    p.controller.velocity.y = 0;
    p.controller.velocity.z = 0;
  }
}

function hook(core: SimCore, name: string, run: () => void): void {
  try {
    run();
  } catch (err) {
    throw new Error(`scenario ${core.def.name}: ${name} failed at tick ${core.currentTick}: ${(err as Error).message}`, { cause: err });
  }
  assertRegistryInSync(core, name);
}

/** Runs one tick for `raw` (validated first: a bad record throws and changes nothing). Returns the tick's events. */
export function runTick(core: SimCore, raw: unknown): SimEvent[] {
  if (core.failure) throw new Error(`the simulation failed at tick ${core.tick} and must be restored from a checkpoint: ${core.failure.message}`);
  const rec: TickInputRecord = validateTickRecord(raw, core.tick, (id) => core.players.has(id), core.gameInputFields, core.gameMessageKinds);
  const after = core.players.size - rec.leaves.length + rec.joins.length;
  if (rec.joins.length > 0 && after > core.rules.maxPlayers) {
    throw new Error(`step(tick ${core.tick}): ${after} players would be in the game, but scenario ${core.def.name} serves at most ${core.rules.maxPlayers} (players.maxPlayers, its per-tick character budget)`);
  }
  const tick = core.tick;
  core.currentTick = tick;
  core.tickEvents = [];
  core.departed.clear();
  core.phase = 'tick';
  try {
    for (const id of rec.leaves) leave(core, id, tick);
    for (const j of rec.joins) join(core, j, tick);
    if (rec.messages && core.instance.onMessage) {
      for (const m of rec.messages) hook(core, 'onMessage', () => core.instance.onMessage!(core.ctx, gameMessageEvent(m, core.gameMessageKinds)));
    }
    // Commands and players both ascend by player id (the record is validated so): one walk pairs them.
    const given = rec.commands;
    let g = 0;
    const applied: PlayerCommand[] = [];
    for (const p of core.players.inOrder()) {
      while (g < given.length && given[g].playerId < p.playerId) g++;
      const cmd = g < given.length && given[g].playerId === p.playerId ? given[g].input : p.input;
      applied.push({ playerId: p.playerId, input: cmd });
      const aim = applyCommand(p, cmd, core.rules, tick);
      if (aim) fire(core, p, aim, tick);
    }
    core.tickInputs = applied;
    for (const p of core.players.inOrder()) p.controller.move(TICK_DT_SECONDS);
    const stepped = core.world.stepFixed();
    if (core.instance.onTick) hook(core, 'onTick', () => core.instance.onTick!(core.ctx));
    expireAndBound(core, tick);
    const raw = core.carriedSensor.concat(stepped, worldInternals(core.world).sensorHub.drain());
    const sensorEvents = sensorSimEvents(core, tick, raw);
    core.tickEvents.push(...sensorEvents);
    if (core.instance.onEvents) hook(core, 'onEvents', () => core.instance.onEvents!(core.ctx, sensorEvents));
    core.carriedSensor = worldInternals(core.world).sensorHub.drain();
  } catch (err) {
    core.failure = err as Error;
    core.phase = 'idle';
    throw err;
  }
  core.tick = tick + 1;
  core.phase = 'idle';
  return core.tickEvents;
}
