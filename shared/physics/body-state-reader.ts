// The bulk body read behind PhysicsWorld.readBodyStates(): the world's bodies in stable-id order, in reused typed
// arrays, read through Jolt's raw exported bindings (no wrapper objects). Only what can have moved is read again: a
// body Jolt keeps active, one that fell asleep or was touched through the world since the last read, every kinematic
// body and character; the others keep the values of their last read, which Jolt cannot have changed.
import { BodyFlag, BODY_STATE_STRIDE } from '../physics-data/body-state.ts';
import type { Vec3Like } from '../physics-data/vectors.ts';
import type { BodyHandle } from './body-handle.ts';
import { BODY_COM_POSITION_WORD, BODY_MOTION_PROPERTIES_WORD, BODY_ROTATION_WORD, BodyMemory, BodyReadMode, MOTION_ANGULAR_VELOCITY_WORD, MOTION_LINEAR_VELOCITY_WORD } from './body-memory.ts';
import type { JoltModule } from './jolt-backend.ts';

type RawGetter = (bodyPtr: number) => number;
type RawGetters = { pos: RawGetter; rot: RawGetter; lin: RawGetter; ang: RawGetter; active: RawGetter };

/** Jolt's BodyID: the index bits (the rest is the sequence number and the broad-phase bit). */
const BODY_INDEX_MASK = 0x7fffff;

/** One raw export of the module (its typings do not list them), if it is a function. */
function rawGetter(J: JoltModule, name: string): RawGetter | undefined {
  const f: unknown = Reflect.get(J, name);
  return typeof f === 'function' ? (f as RawGetter) : undefined;
}

/** The raw Body getters the glue code calls; undefined if this Jolt build does not export them. */
function rawGetters(J: JoltModule): RawGetters | undefined {
  const pos = rawGetter(J, '_emscripten_bind_Body_GetPosition_0');
  const rot = rawGetter(J, '_emscripten_bind_Body_GetRotation_0');
  const lin = rawGetter(J, '_emscripten_bind_Body_GetLinearVelocity_0');
  const ang = rawGetter(J, '_emscripten_bind_Body_GetAngularVelocity_0');
  const active = rawGetter(J, '_emscripten_bind_Body_IsActive_0');
  if (!pos || !rot || !lin || !ang || !active) return undefined;
  return { pos, rot, lin, ang, active };
}

/** The result of a bulk read: views into reused arrays, overwritten by the next read. */
export interface BodyStates {
  count: number;
  ids: Uint32Array;
  states: Float32Array;
  flags: Uint8Array;
}

/** Growable per-Jolt-body-index bytes (the index is below the system's body limit; grown on demand anyway). */
class IndexBytes {
  bytes = new Uint8Array(256);

  get(index: number): number {
    return index < this.bytes.length ? this.bytes[index] : 0;
  }

  set(index: number, value: number): void {
    if (index >= this.bytes.length) {
      const grown = new Uint8Array(Math.max(index + 1, this.bytes.length * 2));
      grown.set(this.bytes);
      this.bytes = grown;
    }
    this.bytes[index] = value;
  }
}

/**
 * Reads every tracked body's pose, velocities and flags. The world tells it of each body added, removed or moved
 * through its API (add / remove / touch) and of every restored physics state (invalidate); Jolt's activation
 * listener tells it which bodies are awake and which fell asleep. The first read, and any after invalidate(), reads
 * every body.
 */
export class BodyStateReader {
  private readonly J: JoltModule;
  private readonly raw: RawGetters | undefined;
  /** Direct heap reads of moving bodies (null: this build lacks what checks them; every read uses the getters). */
  private readonly memory: BodyMemory | null;
  /** Read every body on each read (a reference for tests; always without raw getters or a system to follow). */
  everyBody: boolean;
  private dirty = true;
  /** Whether the world stepped since the last read (only then can an active body have moved by itself). */
  private steppedSinceRead = true;
  private count = 0;
  private handles: BodyHandle[] = [];
  private ptrs = new Int32Array(0);
  private ids = new Uint32Array(0);
  private baseFlags = new Uint8Array(0);
  /** Per slot: the Jolt body index (into `active` and `stale`). */
  private joltIndex = new Int32Array(0);
  /** Per slot: how a read that follows the world reads it (BodyReadMode; reads of every body use the getters). */
  private modes = new Uint8Array(0);
  private readonly knownModes = new WeakMap<BodyHandle, number>();
  private states = new Float32Array(0);
  private flags = new Uint8Array(0);
  /** By Jolt body index: 1 while Jolt keeps the body active (from the activation listener). */
  private readonly active = new IndexBytes();
  /** By Jolt body index: 1 when the body may have changed since its last read without being active now. */
  private readonly stale = new IndexBytes();
  private result: BodyStates = { count: 0, ids: new Uint32Array(0), states: new Float32Array(0), flags: new Uint8Array(0) };
  private readonly listener: InstanceType<JoltModule['BodyActivationListenerJS']> | null;

  /** `system`: the world's, to follow its bodies' activity; without it (or raw getters) every read reads every body. */
  constructor(J: JoltModule, system?: InstanceType<JoltModule['PhysicsSystem']>) {
    this.J = J;
    this.raw = rawGetters(J);
    this.memory = this.raw === undefined || system === undefined ? null : BodyMemory.of(J);
    this.everyBody = this.raw === undefined || system === undefined;
    if (this.raw === undefined || system === undefined) {
      this.listener = null;
      return;
    }
    // Every restored physics state (checkpoints, fast state buffers) goes through the system's RestoreState: the
    // values of the last read no longer hold, so the next read reads every body.
    const restoreState = system.RestoreState.bind(system);
    system.RestoreState = (stream: InstanceType<JoltModule['StateRecorder']>, filter?: InstanceType<JoltModule['StateRecorderFilter']>) => {
      this.dirty = true;
      return restoreState(stream, filter);
    };
    const listener = new J.BodyActivationListenerJS(); // owned by this reader; destroyed in dispose()
    const heapU32 = (): Uint32Array => J.HEAPU32;
    listener.OnBodyActivated = (bodyIdPtr: number) => {
      const index = heapU32()[bodyIdPtr >> 2] & BODY_INDEX_MASK;
      this.active.set(index, 1);
      this.stale.set(index, 1); // its Active flag changed
    };
    listener.OnBodyDeactivated = (bodyIdPtr: number) => {
      const index = heapU32()[bodyIdPtr >> 2] & BODY_INDEX_MASK;
      this.active.set(index, 0);
      this.stale.set(index, 1); // Jolt zeroes its velocities as it falls asleep
    };
    system.SetBodyActivationListener(listener);
    this.listener = listener;
  }

  /** Unhooks and frees the activation listener (before the system goes). */
  dispose(system: InstanceType<JoltModule['PhysicsSystem']>): void {
    if (this.listener === null) return;
    system.SetBodyActivationListener(null as unknown as InstanceType<JoltModule['BodyActivationListener']>);
    this.J.destroy(this.listener);
  }

  /** The world stepped: every active body may have moved. */
  stepped(): void {
    this.steppedSinceRead = true;
  }

  /** Forgets what it read: the next read reads every body (after a restored physics state). */
  invalidate(): void {
    this.dirty = true;
  }

  /** A body was moved, pushed or teleported through the world's API: the next read reads it. */
  touch(h: BodyHandle): void {
    this.stale.set(h.joltId & BODY_INDEX_MASK, 1);
  }

  /** A body joined the world: inserts it at its id's place (appends in the usual case of a fresh, highest id). */
  add(h: BodyHandle): void {
    if (this.dirty) return; // the next read rebuilds from the table, which already holds it
    const n = this.count;
    this.ensureCapacity(n + 1, n);
    const i = n === 0 || this.ids[n - 1] < h.id ? n : lowerBound(this.ids, n, h.id);
    if (i < n) {
      this.ptrs.copyWithin(i + 1, i, n);
      this.ids.copyWithin(i + 1, i, n);
      this.baseFlags.copyWithin(i + 1, i, n);
      this.joltIndex.copyWithin(i + 1, i, n);
      this.modes.copyWithin(i + 1, i, n);
      this.flags.copyWithin(i + 1, i, n);
      this.states.copyWithin((i + 1) * BODY_STATE_STRIDE, i * BODY_STATE_STRIDE, n * BODY_STATE_STRIDE);
      this.handles.splice(i, 0, h);
    } else {
      this.handles.push(h);
    }
    this.put(i, h);
    this.count = n + 1;
  }

  /** A body left the world: closes its gap in the list. */
  remove(h: BodyHandle): void {
    const index = h.joltId & BODY_INDEX_MASK;
    this.active.set(index, 0);
    this.stale.set(index, 0);
    if (this.dirty) return;
    const n = this.count;
    const i = lowerBound(this.ids, n, h.id);
    if (i >= n || this.ids[i] !== h.id) {
      this.dirty = true; // not in the list: never expected, but a rebuild is always right
      return;
    }
    this.ptrs.copyWithin(i, i + 1, n);
    this.ids.copyWithin(i, i + 1, n);
    this.baseFlags.copyWithin(i, i + 1, n);
    this.joltIndex.copyWithin(i, i + 1, n);
    this.modes.copyWithin(i, i + 1, n);
    this.flags.copyWithin(i, i + 1, n);
    this.states.copyWithin(i * BODY_STATE_STRIDE, (i + 1) * BODY_STATE_STRIDE, n * BODY_STATE_STRIDE);
    this.handles.splice(i, 1);
    this.count = n - 1;
  }

  /** Grows the arrays to hold `n` bodies, keeping the first `keep` entries of the list. */
  private ensureCapacity(n: number, keep: number): void {
    if (this.ids.length >= n) return;
    const cap = Math.max(64, n * 2);
    const grow = <T extends Int32Array | Uint32Array | Uint8Array | Float32Array>(old: T, make: (size: number) => T, stride = 1): T => {
      const next = make(cap * stride);
      next.set(old.subarray(0, keep * stride));
      return next;
    };
    this.ptrs = grow(this.ptrs, (s) => new Int32Array(s));
    this.ids = grow(this.ids, (s) => new Uint32Array(s));
    this.baseFlags = grow(this.baseFlags, (s) => new Uint8Array(s));
    this.joltIndex = grow(this.joltIndex, (s) => new Int32Array(s));
    this.modes = grow(this.modes, (s) => new Uint8Array(s));
    this.flags = grow(this.flags, (s) => new Uint8Array(s));
    this.states = grow(this.states, (s) => new Float32Array(s), BODY_STATE_STRIDE);
  }

  /** Writes one body's entry at index i; its state is read on the next read. */
  private put(i: number, h: BodyHandle): void {
    this.ids[i] = h.id;
    this.ptrs[i] = this.J.getPointer(h.raw);
    let f = h.motion === 'static' ? BodyFlag.Static : h.motion === 'kinematic' ? BodyFlag.Kinematic : BodyFlag.Dynamic;
    if (h.isSensor) f |= BodyFlag.Sensor;
    if (h.role === 'character') f |= BodyFlag.Character;
    this.baseFlags[i] = f;
    const index = h.joltId & BODY_INDEX_MASK;
    this.joltIndex[i] = index;
    this.modes[i] = this.memory !== null && (f & BodyFlag.Static) === 0 ? this.readModeOf(h, this.memory) : BodyReadMode.Getters;
    if (this.raw) this.active.set(index, (f & BodyFlag.Static) === 0 && this.raw.active(this.ptrs[i]) ? 1 : 0);
    this.stale.set(index, 1);
  }

  /** A body's read mode, asked of Jolt once per body (its shape never changes): rebuilds after restores reuse it. */
  private readModeOf(h: BodyHandle, memory: BodyMemory): number {
    let mode = this.knownModes.get(h);
    if (mode === undefined) {
      mode = memory.modeFor(this.J.getPointer(h.raw));
      this.knownModes.set(h, mode);
    }
    return mode;
  }

  private rebuild(sortedIds: readonly number[], records: ReadonlyMap<number, BodyHandle>): void {
    const n = sortedIds.length;
    this.ensureCapacity(n, 0);
    this.handles = new Array<BodyHandle>(n);
    for (let i = 0; i < n; i++) {
      const h = records.get(sortedIds[i])!;
      this.handles[i] = h;
      this.put(i, h);
    }
    this.count = n;
    this.dirty = false;
  }

  /**
   * Whether slot i must be read again: woken, fallen asleep or touched since its last read, or a character (Jolt moves
   * their bodies outside the step); after a step also every active body and every kinematic one.
   */
  private mayHaveMoved(i: number, afterStep: boolean): boolean {
    const base = this.baseFlags[i];
    const index = this.joltIndex[i];
    if ((base & BodyFlag.Character) !== 0 || this.stale.get(index) === 1) return true;
    return afterStep && ((base & BodyFlag.Kinematic) !== 0 || this.active.get(index) === 1);
  }

  /**
   * Ids (ascending) of awake non-static bodies whose position is outside [min, max] or not finite. Sleeping bodies
   * are skipped: they have not moved since they fell asleep, and moving one (setPosition, an impulse) wakes it.
   */
  awakeOutside(sortedIds: readonly number[], records: ReadonlyMap<number, BodyHandle>, min: Vec3Like, max: Vec3Like): number[] {
    const out: number[] = [];
    const following = this.raw !== undefined && !this.everyBody && this.listener !== null;
    // Following the world, a read costs only what moved, and the tick's own read after it then costs nothing more.
    const read = following ? this.read(sortedIds, records) : null;
    if (this.dirty) this.rebuild(sortedIds, records);
    for (let i = 0; i < this.count; i++) {
      if ((this.baseFlags[i] & BodyFlag.Static) !== 0) continue;
      let x: number;
      let y: number;
      let z: number;
      if (read !== null) {
        if (this.active.get(this.joltIndex[i]) !== 1) continue;
        const o = i * BODY_STATE_STRIDE;
        x = read.states[o];
        y = read.states[o + 1];
        z = read.states[o + 2];
      } else {
        const h = this.handles[i];
        if (!h.raw.IsActive()) continue;
        ({ x, y, z } = h.position());
      }
      // NaN compares false everywhere, so a body whose state blew up counts as outside.
      if (!(x >= min.x && x <= max.x && y >= min.y && y <= max.y && z >= min.z && z <= max.z)) out.push(this.ids[i]);
    }
    return out;
  }

  /** Reads the bodies that may have moved (all of them when `everyBody` or after invalidate()), ids ascending. */
  read(sortedIds: readonly number[], records: ReadonlyMap<number, BodyHandle>): BodyStates {
    if (this.dirty) this.rebuild(sortedIds, records);
    const n = this.count;
    const states = this.states;
    const flags = this.flags;
    const raw = this.raw;
    if (!raw) {
      for (let i = 0; i < n; i++) {
        const h = this.handles[i];
        h.readStateInto(states, i * BODY_STATE_STRIDE);
        flags[i] = this.baseFlags[i] | ((this.baseFlags[i] & BodyFlag.Static) === 0 && h.raw.IsActive() ? BodyFlag.Active : 0);
      }
      return this.view();
    }
    const every = this.everyBody || this.listener === null;
    const afterStep = this.steppedSinceRead;
    this.steppedSinceRead = false;
    const heap = this.J.HEAPF32;
    const heapU32 = this.J.HEAPU32;
    const { pos, rot, lin, ang, active } = raw;
    const direct = !every && this.memory !== null && this.memory.enabled;
    for (let i = 0; i < n; i++) {
      if (!every && !this.mayHaveMoved(i, afterStep)) continue;
      const b = this.ptrs[i];
      const o = i * BODY_STATE_STRIDE;
      const mode = this.modes[i];
      if (direct && mode !== BodyReadMode.Getters) {
        readDirect(heap, heapU32, b, mode === BodyReadMode.Direct, pos, states, o);
        const base = this.baseFlags[i];
        const index = this.joltIndex[i];
        flags[i] = this.active.get(index) === 1 ? base | BodyFlag.Active : base;
        this.stale.set(index, 0);
        continue;
      }
      let p = pos(b) >> 2;
      states[o] = heap[p];
      states[o + 1] = heap[p + 1];
      states[o + 2] = heap[p + 2];
      p = rot(b) >> 2;
      states[o + 3] = heap[p];
      states[o + 4] = heap[p + 1];
      states[o + 5] = heap[p + 2];
      states[o + 6] = heap[p + 3];
      p = lin(b) >> 2;
      states[o + 7] = heap[p];
      states[o + 8] = heap[p + 1];
      states[o + 9] = heap[p + 2];
      p = ang(b) >> 2;
      states[o + 10] = heap[p];
      states[o + 11] = heap[p + 1];
      states[o + 12] = heap[p + 2];
      const base = this.baseFlags[i];
      const index = this.joltIndex[i];
      const isActive = (base & BodyFlag.Static) === 0 && (every ? active(b) !== 0 : this.active.get(index) === 1);
      flags[i] = isActive ? base | BodyFlag.Active : base;
      this.stale.set(index, 0);
    }
    return this.view();
  }

  /** The reused result object; new views only when the count or the arrays changed. */
  private view(): BodyStates {
    const n = this.count;
    const r = this.result;
    if (r.count !== n || r.ids.buffer !== this.ids.buffer) {
      this.result = { count: n, ids: this.ids.subarray(0, n), states: this.states.subarray(0, n * BODY_STATE_STRIDE), flags: this.flags.subarray(0, n) };
    }
    return this.result;
  }
}

/**
 * One non-static body's 13 floats from the heap (see body-memory.ts): rotation and velocities always; the position
 * from mPosition when `comAtOrigin` and every coordinate and rotation component allows it (finite, coordinates
 * non-zero), else from the getter.
 */
function readDirect(heap: Float32Array, heapU32: Uint32Array, bodyPtr: number, comAtOrigin: boolean, pos: RawGetter, states: Float32Array, o: number): void {
  const q = bodyPtr >> 2;
  const r = q + BODY_ROTATION_WORD;
  const rx = heap[r];
  const ry = heap[r + 1];
  const rz = heap[r + 2];
  const rw = heap[r + 3];
  states[o + 3] = rx;
  states[o + 4] = ry;
  states[o + 5] = rz;
  states[o + 6] = rw;
  const c = q + BODY_COM_POSITION_WORD;
  const x = heap[c];
  const y = heap[c + 1];
  const z = heap[c + 2];
  // x − x is 0 only for a finite x; NaN and ±Infinity fail every comparison below.
  if (comAtOrigin && x !== 0 && y !== 0 && z !== 0 && x - x === 0 && y - y === 0 && z - z === 0 && rx - rx === 0 && ry - ry === 0 && rz - rz === 0 && rw - rw === 0) {
    states[o] = x;
    states[o + 1] = y;
    states[o + 2] = z;
  } else {
    const p = pos(bodyPtr) >> 2;
    states[o] = heap[p];
    states[o + 1] = heap[p + 1];
    states[o + 2] = heap[p + 2];
  }
  const m = heapU32[q + BODY_MOTION_PROPERTIES_WORD] >> 2;
  states[o + 7] = heap[m + MOTION_LINEAR_VELOCITY_WORD];
  states[o + 8] = heap[m + MOTION_LINEAR_VELOCITY_WORD + 1];
  states[o + 9] = heap[m + MOTION_LINEAR_VELOCITY_WORD + 2];
  states[o + 10] = heap[m + MOTION_ANGULAR_VELOCITY_WORD];
  states[o + 11] = heap[m + MOTION_ANGULAR_VELOCITY_WORD + 1];
  states[o + 12] = heap[m + MOTION_ANGULAR_VELOCITY_WORD + 2];
}

/** First index in ids[0, n) whose value is not below `value`. */
function lowerBound(ids: Uint32Array, n: number, value: number): number {
  let lo = 0;
  let hi = n;
  while (lo < hi) {
    const mid = (lo + hi) >>> 1;
    if (ids[mid] < value) lo = mid + 1;
    else hi = mid;
  }
  return lo;
}
