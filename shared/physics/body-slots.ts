// BodySlots: creates every Jolt body of a world at a BodyID chosen by the deterministic BodyIdAllocator (and steers
// Jolt into giving character inner bodies the chosen id too), so checkpoints can restore id allocation exactly.
// Also owns the world's "no-collide group" filter (a shooter and its bullets never touch). Owned by PhysicsWorld.
import { BodyIdAllocator, joltBodyIndex, joltBodySequence, packJoltBodyId, type BodyIdAllocatorState } from './body-id-allocator.ts';
import type { JoltBody } from './body-handle.ts';
import type { JoltModule } from './jolt-backend.ts';
import { CollisionLayer, packObjectLayer } from './layers.ts';

type J = JoltModule;

/** Largest no-collide group id (Jolt reserves 0xffffffff as "no group"). */
export const MAX_NO_COLLIDE_GROUP = 0xfffffffe;

/** Jolt BodyID bookkeeping of one world. */
export class BodySlots {
  readonly allocator: BodyIdAllocator;
  private readonly J: J;
  private readonly bodyInterface: InstanceType<J['BodyInterface']>;
  /** Mirror of Jolt's own per-index sequence counters (bumped only when Jolt picks the id itself). */
  private readonly joltSequences: Uint8Array;
  private readonly probeSettings: InstanceType<J['BodyCreationSettings']>;
  private readonly groupFilter: InstanceType<J['GroupFilterTable']>;
  private disposed = false;

  constructor(Jm: J, bodyInterface: InstanceType<J['BodyInterface']>, capacity: number) {
    this.J = Jm;
    this.bodyInterface = bodyInterface;
    this.allocator = new BodyIdAllocator(capacity);
    this.joltSequences = new Uint8Array(capacity);
    const shape = new Jm.SphereShape(0.05); // referenced by the probe settings below
    const pos = new Jm.RVec3(0, 0, 0); // copied, freed below
    const rot = new Jm.Quat(0, 0, 0, 1); // copied, freed below
    const layer = packObjectLayer(Jm, CollisionLayer.World, CollisionLayer.World);
    this.probeSettings = new Jm.BodyCreationSettings(shape, pos, rot, Jm.EMotionType_Static, layer); // owned here; never added to the world
    Jm.destroy(pos);
    Jm.destroy(rot);
    this.groupFilter = new Jm.GroupFilterTable(1); // ref-counted; our reference is released in dispose()
    this.groupFilter.AddRef();
    this.groupFilter.DisableCollision(0, 0); // same group id ⇒ no collision
  }

  /** Creates (does not add) a body at the next allocated BodyID, or at `joltId` (checkpoint restore). */
  create(settings: InstanceType<J['BodyCreationSettings']>, joltId?: number): JoltBody {
    const J = this.J;
    const target = joltId ?? this.allocator.allocate();
    if (joltId !== undefined) this.allocator.claim(joltId);
    const id = new J.BodyID(target); // copied by CreateBodyWithID, freed below
    const body = this.bodyInterface.CreateBodyWithID(id, settings);
    J.destroy(id);
    if (J.getPointer(body) === 0) {
      this.allocator.release(target);
      throw new Error(`Jolt refused body id ${joltBodyIndex(target)}/${joltBodySequence(target)} (slot taken or beyond maxBodies)`);
    }
    return body;
  }

  /** Frees a body's BodyID for reuse (after Jolt destroyed the body). */
  release(joltId: number): void {
    this.allocator.release(joltId);
  }

  /**
   * Arranges for the next body Jolt allocates itself (a CharacterVirtual's inner body) to get the allocator's next
   * BodyID, or `joltId`: puts its index at the head of Jolt's free list and advances Jolt's sequence counter for it.
   * Returns the id; call confirmJoltChosen() with the id Jolt actually gave.
   */
  prepareJoltChosen(joltId?: number): number {
    const J = this.J;
    const target = joltId ?? this.allocator.allocate();
    if (joltId !== undefined) this.allocator.claim(joltId);
    const index = joltBodyIndex(target);
    const wantSeq = joltBodySequence(target);
    const probeId = new J.BodyID(packJoltBodyId(index, 0)); // copied, freed below
    const probe = this.bodyInterface.CreateBodyWithID(probeId, this.probeSettings);
    J.destroy(probeId);
    if (J.getPointer(probe) === 0) {
      this.allocator.release(target);
      throw new Error(`Jolt refused body slot ${index} while placing a character's inner body`);
    }
    this.bodyInterface.DestroyBody(probe.GetID()); // index is now the head of Jolt's free list
    while (((this.joltSequences[index] + 1) & 0xff) !== wantSeq) {
      const burn = this.bodyInterface.CreateBody(this.probeSettings); // pops our index, bumps its counter
      const got = burn.GetID().GetIndex();
      this.bodyInterface.DestroyBody(burn.GetID());
      if (got !== index) throw new Error(`BodySlots: Jolt reused slot ${got}, expected ${index}`);
      this.joltSequences[index] = (this.joltSequences[index] + 1) & 0xff;
    }
    return target;
  }

  /** Records the id Jolt chose after prepareJoltChosen(); throws if Jolt did not follow the plan. */
  confirmJoltChosen(expected: number, actual: number): void {
    this.joltSequences[joltBodyIndex(actual)] = joltBodySequence(actual);
    if (actual !== expected) {
      throw new Error(`BodySlots: Jolt gave the inner body id ${actual.toString(16)}, expected ${expected.toString(16)}`);
    }
  }

  /** Puts a body creation into no-collide group `group` (bodies sharing a group never collide). */
  applyNoCollideGroup(settings: InstanceType<J['BodyCreationSettings']>, group: number): void {
    const cg = new this.J.CollisionGroup(this.groupFilter, group, 0); // copied into the settings, freed below
    settings.mCollisionGroup = cg;
    this.J.destroy(cg);
  }

  /** Puts an existing body into no-collide group `group`. */
  setNoCollideGroup(body: JoltBody, group: number): void {
    const cg = new this.J.CollisionGroup(this.groupFilter, group, 0); // copied by SetCollisionGroup, freed below
    this.bodyInterface.SetCollisionGroup(body.GetID(), cg);
    this.J.destroy(cg);
  }

  /** The allocator state (checkpoints). */
  save(): BodyIdAllocatorState {
    return this.allocator.save();
  }

  /** Restores the allocator state; `liveJoltIds` are the bodies that exist after the restore. */
  restore(state: BodyIdAllocatorState, liveJoltIds: Iterable<number>): void {
    const indices: number[] = [];
    for (const id of liveJoltIds) indices.push(joltBodyIndex(id));
    this.allocator.restore(state, indices);
  }

  /** Frees the probe settings and the group filter. */
  dispose(): void {
    if (this.disposed) return;
    this.disposed = true;
    this.J.destroy(this.probeSettings); // releases the probe shape
    this.groupFilter.Release();
  }
}

/** Throws unless `group` is a valid no-collide group id. */
export function checkNoCollideGroup(group: unknown, what: string): void {
  if (typeof group !== 'number' || !Number.isInteger(group) || group < 0 || group > MAX_NO_COLLIDE_GROUP) {
    throw new Error(`${what}: noCollideGroup must be an integer in [0, ${MAX_NO_COLLIDE_GROUP}], got ${String(group)}`);
  }
}
