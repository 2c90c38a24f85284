// Checkpoints: capture everything a Simulation needs to resume (Jolt SaveState(All), each CharacterVirtual, the
// JS-side state) and restore it, removing bodies and players added since and recreating those removed since
// under their original stable ids and Jolt BodyIDs. The fast form keeps Jolt's bytes on the WASM heap.
import { FastStateBuffer, type BodyIdAllocatorState, type SensorEvent } from '../physics/index.ts';
import { worldInternals } from '../physics/internal.ts';
import type { BodyRecord } from './body-registry.ts';
import type { Bullet } from './bullets.ts';
import type { GameStateValue } from './game-state.ts';
import { createCharacter, type PlayerSnapshot } from './players.ts';
import { destroyBody, recreateBody, type SimCore } from './sim-core.ts';

/** The JS-side state of a checkpoint (shared by the fast and the byte form). */
export interface CheckpointData {
  tick: number;
  prng: number[];
  joinCount: number;
  nextBodyId: number;
  slots: BodyIdAllocatorState;
  players: PlayerSnapshot[];
  /** CharacterController.saveState() bytes by player id. */
  characterStates: Map<number, Uint8Array>;
  bullets: Bullet[];
  /** Every live body's record (characters included), ascending id. */
  records: BodyRecord[];
  scenarioState: number[] | null;
  /** Game state values in field order (empty when the scenario declares none). */
  gameState: GameStateValue[];
  /** SensorHub.exportOverlaps() rows. */
  overlaps: number[];
  carriedSensor: SensorEvent[];
  constraintCount: number;
}

/** What a fast checkpoint holds; only this module reads it (through contentsOf). */
interface CheckpointContents {
  readonly data: CheckpointData;
  readonly physics: FastStateBuffer;
  /** The simulation core that made it (fast checkpoints restore only into their own simulation). */
  readonly owner: SimCore;
}

let contentsOf: (cp: Checkpoint) => CheckpointContents;

/** The fast in-memory checkpoint. Holds WASM memory: call dispose() when it is no longer needed. */
export class Checkpoint {
  /** The tick the simulation will apply next after a restore (ticks applied when saved). */
  readonly tick: number;
  private readonly data: CheckpointData;
  private readonly physics: FastStateBuffer;
  private readonly owner: SimCore;
  private disposed = false;

  static {
    contentsOf = (cp) => ({ data: cp.data, physics: cp.physics, owner: cp.owner });
  }

  constructor(owner: SimCore, data: CheckpointData, physics: FastStateBuffer) {
    this.owner = owner;
    this.data = data;
    this.physics = physics;
    this.tick = data.tick;
  }

  /** Frees the Jolt state buffer. */
  dispose(): void {
    if (this.disposed) return;
    this.disposed = true;
    this.physics.dispose();
  }

  /** Whether dispose() has run. */
  get isDisposed(): boolean {
    return this.disposed;
  }
}

function assertCheckpointable(core: SimCore, what: string): void {
  if (core.phase !== 'idle') throw new Error(`${what}: not allowed inside a tick`);
  if (core.failure) throw new Error(`${what}: the simulation failed at tick ${core.tick} (${core.failure.message}); restore a checkpoint first`);
}

/** Copies the JS-side state and every character's Jolt state. */
export function captureData(core: SimCore, what: string): CheckpointData {
  assertCheckpointable(core, what);
  const characterStates = new Map<number, Uint8Array>();
  for (const p of core.players.inOrder()) characterStates.set(p.playerId, p.controller.saveState());
  return {
    tick: core.tick,
    prng: core.rng.getState(),
    joinCount: core.players.joinCount,
    nextBodyId: core.world.nextId,
    slots: worldInternals(core.world).slots.save(),
    players: core.players.snapshot(),
    characterStates,
    bullets: core.bullets.snapshot(),
    records: core.registry.all(),
    scenarioState: core.instance.saveState ? core.instance.saveState().slice() : null,
    gameState: core.gameState.list(),
    overlaps: worldInternals(core.world).sensorHub.exportOverlaps(),
    carriedSensor: core.carriedSensor.map((e) => ({ ...e })),
    constraintCount: core.world.constraintCount,
  };
}

/** Saves a fast checkpoint (Jolt state in a StateRecorderImpl on the WASM heap). */
export function saveCheckpoint(core: SimCore): Checkpoint {
  const data = captureData(core, 'saveCheckpoint');
  const J = core.world.jolt;
  const buffer = new FastStateBuffer(J); // owned by the Checkpoint; freed by its dispose()
  try {
    buffer.saveWorld(core.world); // checks the heap first: the buffer grows there, and running out would abort
  } catch (err) {
    buffer.dispose();
    throw err;
  }
  return new Checkpoint(core, data, buffer);
}

/**
 * Puts `core` into the state of `data`. `restorePhysics` runs Jolt's RestoreState once the body set matches;
 * `sameBody` says whether a live body may stay (identical recipe and ids) or must be rebuilt from its saved record.
 */
export function restoreData(core: SimCore, data: CheckpointData, restorePhysics: () => boolean, sameBody: (live: BodyRecord, saved: BodyRecord) => boolean): void {
  const world = core.world;
  if (core.phase !== 'idle') throw new Error('restoreCheckpoint: not allowed inside a tick');
  if (world.constraintCount !== data.constraintCount) {
    throw new Error(
      `restoreCheckpoint: the world has ${world.constraintCount} constraints but the checkpoint ${data.constraintCount}; ` +
        'checkpoints cannot recreate constraints (create them while building and keep their bodies in bounds)',
    );
  }
  try {
    // Bodies a failed hook created behind the simulation's back are not in the registry: drop them first.
    for (const id of world.bodyIds()) {
      const h = world.getBody(id)!;
      if (!core.registry.has(id) && h.role !== 'character') world.removeBody(id);
    }
    const savedPlayers = new Map(data.players.map((p) => [p.playerId, p]));
    for (const p of [...core.players.inOrder()]) {
      const s = savedPlayers.get(p.playerId);
      if (s && s.bodyId === p.bodyId && s.joltId === p.controller.body!.joltId && s.joinIndex === p.joinIndex) continue;
      core.players.remove(p.playerId);
      core.registry.delete(p.bodyId);
    }
    const wanted = new Map<number, BodyRecord>();
    for (const r of data.records) if (r.kind !== 'character') wanted.set(r.id, r);
    for (const live of core.registry.all()) {
      if (live.kind === 'character') continue;
      const w = wanted.get(live.id);
      if (!w || w.joltId !== live.joltId || !sameBody(live, w)) destroyBody(core, live.id);
    }
    if (world.constraintCount !== data.constraintCount) throw new Error('restoreCheckpoint: a body holding a constraint had changed since the checkpoint');
    for (const r of data.records) if (r.kind !== 'character' && !core.registry.has(r.id)) recreateBody(core, r);
    const charRecords = new Map(data.records.filter((r) => r.kind === 'character').map((r) => [r.id, r]));
    for (const s of data.players) {
      let p = core.players.get(s.playerId);
      if (!p) {
        const rec = charRecords.get(s.bodyId);
        if (!rec) throw new Error(`restoreCheckpoint: no body record for player ${s.playerId}'s character ${s.bodyId}`);
        const controller = createCharacter(world, core.rules, s.playerId, s.joinIndex, rec.position, { id: s.bodyId, joltId: s.joltId });
        p = { playerId: s.playerId, name: s.name, joinIndex: s.joinIndex, controller, bodyId: s.bodyId, input: { ...s.input }, nextFireTick: s.nextFireTick };
        core.players.add(p);
      }
      p.input = { ...s.input };
      p.nextFireTick = s.nextFireTick;
    }
    core.registry.replaceAll(data.records);
    if (world.bodyCount !== core.registry.size) throw new Error(`restoreCheckpoint: ${world.bodyCount} bodies in the world, ${core.registry.size} in the checkpoint`);
    const internals = worldInternals(world);
    internals.slots.restore(data.slots, data.records.map((r) => r.joltId));
    internals.setNextBodyId(data.nextBodyId);
    if (!restorePhysics()) throw new Error('restoreCheckpoint: Jolt refused the physics state (body set mismatch)');
    for (const p of core.players.inOrder()) {
      const bytes = data.characterStates.get(p.playerId);
      if (!bytes) throw new Error(`restoreCheckpoint: no character state for player ${p.playerId}`);
      p.controller.restoreState(bytes);
    }
    internals.sensorHub.importOverlaps(data.overlaps);
    core.carriedSensor = data.carriedSensor.map((e) => ({ ...e }));
    core.rng.setState(data.prng);
    core.tick = data.tick;
    core.currentTick = data.tick;
    core.players.joinCount = data.joinCount;
    core.bullets.restore(data.bullets);
    if (data.scenarioState && core.instance.restoreState) core.instance.restoreState(data.scenarioState.slice());
    core.gameState.restore(data.gameState);
    core.tickEvents = [];
    core.failure = null;
  } catch (err) {
    core.failure = err as Error;
    throw err;
  }
}

/** Restores a fast checkpoint made by the same simulation. */
export function restoreCheckpoint(core: SimCore, cp: Checkpoint): void {
  if (!(cp instanceof Checkpoint)) throw new Error('restoreCheckpoint: expected a Checkpoint from saveCheckpoint()');
  if (cp.isDisposed) throw new Error('restoreCheckpoint: the checkpoint was disposed');
  const { owner, data, physics } = contentsOf(cp);
  if (owner !== core) throw new Error('restoreCheckpoint: a fast checkpoint restores only into the simulation that saved it (use the byte form)');
  restoreData(core, data, () => physics.restore((r) => core.world.system.RestoreState(r)), (live, saved) => live === saved);
}
