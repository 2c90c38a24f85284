// The ScenarioContext a Simulation hands its scenario: spawn/remove with events and records, emit, the tick, the
// characters and the tick's inputs. Rejects what a checkpoint could not carry (callbacks on bodies spawned mid-run).
import type { BodyHandle, QuatLike, ShapeSpec, Vec3Like } from '../physics/index.ts';
import { gameInputValues, type GameInputValues } from './game-input.ts';
import type { ScenarioContext, SpawnOptions } from './scenario.ts';
import { createBody, destroyBody, type SimBase } from './sim-core.ts';

/** Longest scenario event name. */
const MAX_EVENT_NAME = 64;

/** Builds the context object for `core` (one per simulation; `tick` reads live). */
export function makeScenarioContext(core: SimBase): ScenarioContext {
  return {
    world: core.world,
    rng: core.rng,
    params: core.params,
    get tick(): number {
      return core.currentTick;
    },
    spawn(shape: ShapeSpec, position: Vec3Like, rotation?: QuatLike | null, opts: SpawnOptions = {}): BodyHandle {
      const building = core.phase === 'building';
      if (!building && core.phase !== 'tick') throw new Error('ctx.spawn: only while building or inside a tick hook');
      if (!building && opts?.sensor !== undefined) {
        throw new Error(
          'ctx.spawn: a body spawned during ticks cannot carry sensor callbacks (they would not survive a checkpoint); ' +
            'spawn it with isSensor: true and react to its sensorEnter/sensorExit events in onEvents',
        );
      }
      const record = createBody(core, building ? 'scene' : 'spawn', shape, position, rotation ?? null, opts ?? {});
      if (!building) core.tickEvents.push({ type: 'bodySpawned', tick: core.currentTick, bodyId: record.id });
      return core.world.getBody(record.id)!;
    },
    remove(bodyId: number): void {
      if (core.phase !== 'tick') throw new Error('ctx.remove: only inside a tick hook');
      const rec = core.registry.get(bodyId);
      if (!rec) throw new Error(`ctx.remove: no body ${String(bodyId)} in the world`);
      if (rec.kind !== 'scene' && rec.kind !== 'spawn') throw new Error(`ctx.remove: body ${bodyId} is a ${rec.kind}, not a scenario body`);
      destroyBody(core, bodyId);
      core.tickEvents.push({ type: 'bodyRemoved', tick: core.currentTick, bodyId });
    },
    emit(name: string, value: number): void {
      if (typeof name !== 'string' || name.length === 0 || name.length > MAX_EVENT_NAME) {
        throw new Error(`ctx.emit: event name must be a string of 1..${MAX_EVENT_NAME} characters, got ${JSON.stringify(name)}`);
      }
      if (typeof value !== 'number' || !Number.isFinite(value)) throw new Error(`ctx.emit(${name}): value must be a finite number, got ${String(value)}`);
      if (core.phase !== 'tick') throw new Error('ctx.emit: only inside a tick hook');
      core.tickEvents.push({ type: 'scenario', tick: core.currentTick, name, value });
    },
    characters() {
      return core.players.characterStates();
    },
    inputs() {
      return core.tickInputs;
    },
    gameInput(playerId: number): GameInputValues {
      const applied = core.tickInputs.find((c) => c.playerId === playerId)?.input ?? core.players.get(playerId)?.input;
      if (applied === undefined) throw new Error(`ctx.gameInput: player ${String(playerId)} is not in the game`);
      return gameInputValues(applied.game, core.gameInputFields);
    },
    setState(name: string, value: number | string): void {
      if (core.phase !== 'building' && core.phase !== 'tick') throw new Error('ctx.setState: only while building or inside a tick hook');
      core.gameState.set(name, value);
    },
    getState(name: string): number | string {
      return core.gameState.get(name);
    },
  };
}
