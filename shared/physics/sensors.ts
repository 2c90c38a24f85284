// Sensor events: one lazily installed Jolt contact listener that counts overlaps per (sensor, other) body pair,
// queues enter/exit during the step and delivers them after it, sorted by (sensor id, other id, exit before enter).
import type { JoltModule } from './jolt-backend.ts';

/** One sensor transition, in stable body ids. */
export interface SensorEvent {
  kind: 'enter' | 'exit';
  sensorId: number;
  otherId: number;
}

/** What the hub needs from the world: map Jolt body ids to stable ids and to sensor-ness. */
export interface SensorRegistry {
  stableIdOf(joltId: number): number | undefined;
  isSensorJoltId(joltId: number): boolean;
  isStaticJoltId(joltId: number): boolean;
}

type ListenerJS = InstanceType<JoltModule['ContactListenerJS']>;

/** Pair key: sensor and other Jolt ids (each < 2^32), packed into one number-safe string-free key. */
function pairKey(sensorJoltId: number, otherJoltId: number): bigint {
  return (BigInt(sensorJoltId) << 32n) | BigInt(otherJoltId);
}

/** Collects sensor overlaps from Jolt callbacks; the world flushes them after each step. */
export class SensorHub {
  private listener: ListenerJS | null = null;
  private readonly counts = new Map<bigint, { sensorId: number; otherId: number; count: number }>();
  private pending: SensorEvent[] = [];
  private readonly J: JoltModule;
  private readonly system: InstanceType<JoltModule['PhysicsSystem']>;
  private readonly registry: SensorRegistry;

  constructor(J: JoltModule, system: InstanceType<JoltModule['PhysicsSystem']>, registry: SensorRegistry) {
    this.J = J;
    this.system = system;
    this.registry = registry;
  }

  /** Installs the contact listener the first time a sensor exists. */
  ensureInstalled(): void {
    if (this.listener) return;
    const J = this.J;
    const listener = new J.ContactListenerJS(); // owned by this hub; destroyed in dispose()
    const bodyJoltId = (ptr: number): number => J.wrapPointer(ptr, J.Body).GetID().GetIndexAndSequenceNumber();
    listener.OnContactValidate = () => J.ValidateResult_AcceptAllContactsForThisBodyPair;
    listener.OnContactAdded = (body1: number, body2: number) => {
      this.added(bodyJoltId(body1), bodyJoltId(body2));
    };
    listener.OnContactPersisted = () => {};
    listener.OnContactRemoved = (subShapePair: number) => {
      const pair = J.wrapPointer(subShapePair, J.SubShapeIDPair);
      this.removed(pair.GetBody1ID().GetIndexAndSequenceNumber(), pair.GetBody2ID().GetIndexAndSequenceNumber());
    };
    this.system.SetContactListener(listener);
    this.listener = listener;
  }

  /** [sensor, other] for a pair a sensor reports; null for pairs it ignores (no sensor, two sensors, a static other). */
  private orient(a: number, b: number): [number, number] | null {
    const sa = this.registry.isSensorJoltId(a);
    const sb = this.registry.isSensorJoltId(b);
    if (sa === sb) return null;
    const pair: [number, number] = sa ? [a, b] : [b, a];
    return this.registry.isStaticJoltId(pair[1]) ? null : pair;
  }

  private added(a: number, b: number): void {
    const pair = this.orient(a, b);
    if (!pair) return;
    const key = pairKey(pair[0], pair[1]);
    const entry = this.counts.get(key);
    if (entry) {
      entry.count++;
      return;
    }
    const sensorId = this.registry.stableIdOf(pair[0]);
    const otherId = this.registry.stableIdOf(pair[1]);
    if (sensorId === undefined || otherId === undefined) return;
    this.counts.set(key, { sensorId, otherId, count: 1 });
    this.pending.push({ kind: 'enter', sensorId, otherId });
  }

  private removed(a: number, b: number): void {
    const pair = this.orient(a, b);
    if (!pair) return;
    const key = pairKey(pair[0], pair[1]);
    const entry = this.counts.get(key);
    if (!entry) return; // already closed (the body was removed)
    entry.count--;
    if (entry.count > 0) return;
    this.counts.delete(key);
    this.pending.push({ kind: 'exit', sensorId: entry.sensorId, otherId: entry.otherId });
  }

  /** Closes every open overlap of a body that is being removed (queues exits for its partners). */
  forgetBody(joltId: number): void {
    for (const [key, entry] of this.counts) {
      const sensorJolt = Number(key >> 32n);
      const otherJolt = Number(key & 0xffffffffn);
      if (sensorJolt !== joltId && otherJolt !== joltId) continue;
      this.counts.delete(key);
      this.pending.push({ kind: 'exit', sensorId: entry.sensorId, otherId: entry.otherId });
    }
  }

  /** Stable ids of the bodies currently inside a sensor, ascending. */
  overlapping(sensorId: number): number[] {
    const out: number[] = [];
    for (const entry of this.counts.values()) if (entry.sensorId === sensorId) out.push(entry.otherId);
    return out.sort((a, b) => a - b);
  }

  /** Takes the queued events in deterministic order: (sensor id, other id), exit before enter for one pair. */
  drain(): SensorEvent[] {
    if (this.pending.length === 0) return [];
    const events = this.pending;
    this.pending = [];
    events.sort((a, b) => a.sensorId - b.sensorId || a.otherId - b.otherId || (a.kind === b.kind ? 0 : a.kind === 'exit' ? -1 : 1));
    return events;
  }

  /** Open overlaps as (sensorJoltId, otherJoltId, sensorId, otherId, count) rows, for checkpoints. */
  exportOverlaps(): number[] {
    const rows: number[] = [];
    const keys = [...this.counts.keys()].sort((a, b) => (a < b ? -1 : a > b ? 1 : 0));
    for (const key of keys) {
      const e = this.counts.get(key)!;
      rows.push(Number(key >> 32n), Number(key & 0xffffffffn), e.sensorId, e.otherId, e.count);
    }
    return rows;
  }

  /** Replaces the open overlaps (checkpoint restore); pending events are dropped. */
  importOverlaps(rows: readonly number[]): void {
    this.counts.clear();
    this.pending = [];
    for (let i = 0; i + 4 < rows.length; i += 5) {
      this.counts.set(pairKey(rows[i], rows[i + 1]), { sensorId: rows[i + 2], otherId: rows[i + 3], count: rows[i + 4] });
    }
  }

  /** Detaches and frees the listener. */
  dispose(): void {
    if (this.listener) {
      this.J.destroy(this.listener);
      this.listener = null;
    }
    this.counts.clear();
    this.pending = [];
  }

  /** Whether the listener is installed. */
  get installed(): boolean {
    return this.listener !== null;
  }
}
