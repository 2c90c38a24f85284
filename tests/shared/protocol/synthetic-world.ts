// Test helper: a seeded synthetic world (no Jolt) that moves, rotates, sleeps, spawns and removes bodies and
// characters every tick, and renders itself as the simulation's bulk read for the snapshot codec.
import { BodyFlag } from '../../../shared/physics-data/body-state.ts';
import type { BodyStatesRead } from '../../../shared/protocol/snapshot-frame.ts';
import { Prng } from '../../../shared/sim/prng.ts';
import type { BodyDescriptor, CharacterState } from '../../../shared/sim/types.ts';

interface SynthBody {
  id: number;
  p: [number, number, number];
  q: [number, number, number, number];
  active: boolean;
  kinematic: boolean;
}

/** Rates of change per tick. */
export interface SyntheticWorldOptions {
  seed?: number;
  bodies?: number;
  characters?: number;
  moveChance?: number;
  spawnChance?: number;
  removeChance?: number;
  sleepChance?: number;
  joinChance?: number;
  leaveChance?: number;
  /** Half extent of the region positions stay in (m). */
  extent?: number;
}

/** A world whose state changes randomly but deterministically per seed. */
export class SyntheticWorld {
  tick = 0;
  readonly bodies: SynthBody[] = [];
  readonly characters = new Map<number, CharacterState>();
  private nextId = 0;
  private nextPlayer = 1;
  private readonly rng: Prng;
  private readonly o: Required<SyntheticWorldOptions>;

  constructor(opts: SyntheticWorldOptions = {}) {
    this.o = {
      seed: 1,
      bodies: 200,
      characters: 3,
      moveChance: 0.3,
      spawnChance: 0.2,
      removeChance: 0.2,
      sleepChance: 0.02,
      joinChance: 0.02,
      leaveChance: 0.01,
      extent: 40,
      ...opts,
    };
    this.rng = new Prng(this.o.seed);
    for (let i = 0; i < this.o.bodies; i++) this.spawn();
    for (let i = 0; i < this.o.characters; i++) this.join();
  }

  private rand(a: number, b: number): number {
    return this.rng.range(a, b);
  }

  private spawn(): void {
    const e = this.o.extent;
    const q: [number, number, number, number] = [this.rand(-1, 1), this.rand(-1, 1), this.rand(-1, 1), this.rand(-1, 1)];
    const n = Math.sqrt(q[0] * q[0] + q[1] * q[1] + q[2] * q[2] + q[3] * q[3]) || 1;
    this.bodies.push({
      id: this.nextId++,
      p: [this.rand(-e, e), this.rand(0, e), this.rand(-e, e)],
      q: [q[0] / n, q[1] / n, q[2] / n, q[3] / n],
      active: true,
      kinematic: this.rng.next() < 0.1,
    });
  }

  private join(): void {
    const id = this.nextPlayer++;
    this.characters.set(id, {
      playerId: id,
      bodyId: 100000 + id,
      position: { x: this.rand(-10, 10), y: 1, z: this.rand(-10, 10) },
      velocity: { x: 0, y: 0, z: 0 },
      yaw: this.rand(0, 6.28),
      pitch: 0,
      groundState: 'ground',
      buttons: 0,
    });
  }

  /** Advances one tick of random changes. */
  step(): void {
    this.tick++;
    const e = this.o.extent;
    for (const b of this.bodies) {
      if (this.rng.next() < this.o.sleepChance) b.active = !b.active;
      if (!b.active || this.rng.next() >= this.o.moveChance) continue;
      const big = this.rng.next() < 0.05 ? 5 : 0.05;
      for (let k = 0; k < 3; k++) b.p[k] = Math.max(-e, Math.min(e, b.p[k] + this.rand(-big, big)));
      if (this.rng.next() < 0.5) {
        const dq = this.rng.next() < 0.05 ? 1 : 0.02;
        for (let k = 0; k < 4; k++) b.q[k] += this.rand(-dq, dq);
        const n = Math.sqrt(b.q[0] ** 2 + b.q[1] ** 2 + b.q[2] ** 2 + b.q[3] ** 2) || 1;
        for (let k = 0; k < 4; k++) b.q[k] /= n;
      }
    }
    if (this.rng.next() < this.o.spawnChance) this.spawn();
    if (this.bodies.length > 0 && this.rng.next() < this.o.removeChance) this.bodies.splice(this.rng.int(0, this.bodies.length - 1), 1);
    for (const c of this.characters.values()) {
      if (this.rng.next() < 0.5) {
        c.position = { x: c.position.x + this.rand(-0.1, 0.1), y: Math.max(0, c.position.y + this.rand(-0.05, 0.05)), z: c.position.z + this.rand(-0.1, 0.1) };
        c.velocity = { x: this.rand(-6, 6), y: this.rand(-3, 3), z: this.rand(-6, 6) };
      }
      if (this.rng.next() < 0.3) c.yaw += this.rand(-0.5, 0.5);
      if (this.rng.next() < 0.1) c.pitch = this.rand(-1.5, 1.5);
      if (this.rng.next() < 0.05) c.groundState = this.rng.pick(['ground', 'steep', 'air', 'unsupported'] as const);
      if (this.rng.next() < 0.05) c.buttons = this.rng.int(0, 15);
      if (this.rng.next() < 0.01) c.bodyId++;
    }
    if (this.rng.next() < this.o.joinChance) this.join();
    if (this.characters.size > 0 && this.rng.next() < this.o.leaveChance) {
      const ids = [...this.characters.keys()];
      this.characters.delete(ids[this.rng.int(0, ids.length - 1)]);
    }
  }

  /** The bulk read, ids ascending, with one static body (id −) that snapshots must skip. */
  read(): BodyStatesRead {
    const list = [...this.bodies].sort((a, b) => a.id - b.id);
    const n = list.length + 1;
    const ids = new Uint32Array(n);
    const states = new Float32Array(n * 13);
    const flags = new Uint8Array(n);
    // A static ground body with the largest id: present in the read, never in snapshots.
    ids[n - 1] = 0x7000_0000;
    flags[n - 1] = BodyFlag.Static;
    states[(n - 1) * 13 + 6] = 1;
    list.forEach((b, i) => {
      ids[i] = b.id;
      states.set([...b.p, ...b.q], i * 13);
      flags[i] = (b.kinematic ? BodyFlag.Kinematic : BodyFlag.Dynamic) | (b.active ? BodyFlag.Active : 0);
    });
    return { count: n, ids, states, flags };
  }

  /** Characters as the simulation reports them. */
  characterStates(): CharacterState[] {
    return [...this.characters.values()].map((c) => ({ ...c, position: { ...c.position }, velocity: { ...c.velocity } }));
  }

  /** A descriptor for any body id. */
  describe(id: number): BodyDescriptor {
    return { id, shape: { kind: 'box', halfExtents: { x: 0.5, y: 0.5, z: 0.5 } }, color: [0.8, 0.3, 0.2], motion: 'dynamic', hidden: false, position: { x: 0, y: 0, z: 0 }, rotation: { x: 0, y: 0, z: 0, w: 1 } };
  }
}

/** Bounds that contain the synthetic world. */
export const SYNTH_BOUNDS = { min: { x: -64, y: -8, z: -64 }, max: { x: 64, y: 64, z: 64 } };
