// Turns what the server says (body descriptors, interpolated snapshot views, events) into what the renderer draws:
// registers bodies, applies poses, shows spawns/removals/descriptor changes at their tick, lights occupied sensors.
import type { SnapshotView } from '../../shared/protocol/snapshot-frame.ts';
import type { BodyDescriptor, SimEvent } from '../../shared/sim/types.ts';
import type { BodyStyle } from '../render/instance-store.ts';
import { BoxOccluders } from '../render/occluders.ts';
import type { Renderer } from '../render/renderer.ts';
import { InstanceFlag } from '../render/shaders.ts';

/** Brightness added to a hidden sensor volume while something is inside it. */
const OCCUPIED_EMISSIVE = 1.6;
/** An empty sensor volume is drawn at this fraction of its colour (dim), an occupied one at full colour and lit. */
const IDLE_SENSOR_SHADE = 0.4;

/** A body as it was when its removal took effect. */
export interface RemovedBody {
  descriptor: BodyDescriptor;
  /** Its last drawn pose (px, py, pz, qx, qy, qz, qw), or null if it was never drawn. */
  pose: readonly number[] | null;
}

interface Known {
  descriptor: BodyDescriptor;
  /** Registered with the renderer (false when its shape was refused). */
  drawn: boolean;
  /** Drawn only while snapshots carry it: moving bodies and statics streamed in after the scene was built. */
  presenceDriven: boolean;
}

/** The part of the Renderer the world view drives (a fake in unit tests). */
export type RenderTarget = Pick<Renderer, 'addBody' | 'removeBody' | 'store'>;

/** Bodies, sensors and events of one session, mirrored into a Renderer. */
export class WorldView {
  private readonly renderer: RenderTarget;
  private readonly log: (line: string) => void;
  private readonly known = new Map<number, Known>();
  /** Descriptors waiting for the render time to reach the tick that carried them (ascending tick). */
  private pendingDescriptors: Array<{ tick: number; descriptor: BodyDescriptor }> = [];
  /** Events waiting for the render time to reach their tick (ascending tick). */
  private pendingEvents: SimEvent[] = [];
  /** Sensor id → body ids inside it. */
  private readonly occupants = new Map<number, Set<number>>();
  private visible = new Set<number>();
  private staticCount = 0;
  /** Bodies in views with no descriptor (a protocol problem worth surfacing). */
  undescribed = 0;
  /** Static solid boxes, for the follow camera to stay out of walls. */
  readonly occluders = new BoxOccluders();
  /** Called with each event as it takes effect (a removed body's descriptor and last pose come with its removal). */
  onEvent: ((e: SimEvent, removed: RemovedBody | null) => void) | null = null;

  constructor(renderer: RenderTarget, log: (line: string) => void) {
    this.renderer = renderer;
    this.log = log;
  }

  /** Starts over with a welcome's static and live bodies. */
  reset(staticBodies: readonly BodyDescriptor[], dynamicBodies: readonly BodyDescriptor[]): void {
    for (const id of [...this.known.keys()]) this.forget(id);
    this.pendingDescriptors = [];
    this.pendingEvents = [];
    this.occupants.clear();
    this.visible.clear();
    this.staticCount = 0;
    for (const d of staticBodies) if (this.register(d, false)) this.staticCount++;
    // The welcome's other bodies, streamed statics among them, are drawn once a snapshot places them.
    for (const d of dynamicBodies) this.register(d, true);
  }

  /** Descriptors that came with the snapshot of `tick` (spawns; possibly repeats or a reused id's new body). */
  addDescriptors(tick: number, descriptors: readonly BodyDescriptor[]): void {
    for (const d of descriptors) {
      const k = this.known.get(d.id);
      if (!k) this.register(d, true);
      else if (!sameLook(k.descriptor, d)) {
        this.pendingDescriptors.push({ tick, descriptor: d });
        this.pendingDescriptors.sort((a, b) => a.tick - b.tick);
      }
    }
  }

  /** Queues events; each takes effect when the render time reaches its tick. */
  queueEvents(events: readonly SimEvent[]): void {
    if (events.length === 0) return;
    this.pendingEvents.push(...events);
    this.pendingEvents.sort((a, b) => a.tick - b.tick);
  }

  /** Applies the interpolated view for this frame: due descriptors and events, then poses and visibility. */
  apply(view: SnapshotView | null, renderTick: number): void {
    while (this.pendingDescriptors.length > 0 && this.pendingDescriptors[0].tick <= renderTick) {
      const { descriptor } = this.pendingDescriptors.shift()!;
      this.forget(descriptor.id);
      this.register(descriptor, true);
    }
    while (this.pendingEvents.length > 0 && this.pendingEvents[0].tick <= renderTick) this.applyEvent(this.pendingEvents.shift()!);
    if (!view) return;
    const store = this.renderer.store;
    const seen = new Set<number>();
    for (let i = 0; i < view.ids.length; i++) {
      const id = view.ids[i];
      const k = this.known.get(id);
      if (!k) {
        this.undescribed++;
        continue;
      }
      if (!k.drawn || !k.presenceDriven) continue;
      // A streamed static keeps its descriptor pose (uploaded once); moving bodies take the interpolated one.
      if (k.descriptor.motion !== 'static') {
        const p = i * 3;
        const q = i * 4;
        store.setPose(id, view.positions[p], view.positions[p + 1], view.positions[p + 2], view.rotations[q], view.rotations[q + 1], view.rotations[q + 2], view.rotations[q + 3]);
      }
      seen.add(id);
      if (!this.visible.has(id)) store.setStyle(id, { visible: true });
    }
    for (const id of this.visible) if (!seen.has(id)) store.setStyle(id, { visible: false });
    this.visible = seen;
  }

  /** Sensors (hidden static volumes and any body named by a sensor event): something inside? drawn lit? */
  sensors(): Array<{ sensorId: number; occupied: boolean; lit: boolean }> {
    return [...this.occupants.entries()]
      .sort((a, b) => a[0] - b[0])
      .map(([sensorId, set]) => ({ sensorId, occupied: set.size > 0, lit: (this.renderer.store.style(sensorId)?.emissive ?? 0) > 0 }));
  }

  /** Bodies drawn this frame (the built scene + bodies the current view carries). */
  get drawnCount(): number {
    return this.staticCount + this.visible.size;
  }

  /** Descriptors of the static bodies known (the scene's fixed geometry). */
  staticDescriptors(): BodyDescriptor[] {
    const out: BodyDescriptor[] = [];
    for (const k of this.known.values()) if (k.descriptor.motion === 'static') out.push(k.descriptor);
    return out;
  }

  /** A known body's descriptor. */
  descriptor(id: number): BodyDescriptor | undefined {
    return this.known.get(id)?.descriptor;
  }

  private register(d: BodyDescriptor, presenceDriven: boolean): boolean {
    const hidden = d.hidden;
    const style: Partial<BodyStyle> = {
      color: hidden ? shade(d.color, IDLE_SENSOR_SHADE) : d.color,
      // Hidden bodies are trigger volumes: draw a box's edges, or any other shape hatched, so players see the zone.
      flags: hidden ? (d.shape.kind === 'box' ? InstanceFlag.Outline : InstanceFlag.Hatch) : d.motion === 'static' ? InstanceFlag.Grid : 0,
      // Bodies that snapshots carry stay hidden until one places them (a spawn appears at its tick).
      visible: !presenceDriven,
    };
    let drawn = true;
    try {
      this.renderer.addBody(d.id, { shape: d.shape, isStatic: d.motion === 'static', position: d.position, rotation: d.rotation, style });
    } catch (err) {
      drawn = false;
      console.warn(`not drawing body ${d.id}: ${(err as Error).message}`);
    }
    this.known.set(d.id, { descriptor: d, drawn, presenceDriven });
    if (d.motion === 'static' && !hidden && d.shape.kind === 'box') this.occluders.set(d.id, d.position, d.rotation, d.shape.halfExtents);
    if (hidden && d.motion === 'static' && !this.occupants.has(d.id)) this.occupants.set(d.id, new Set());
    return drawn;
  }

  private forget(id: number): void {
    const k = this.known.get(id);
    if (!k) return;
    if (k.drawn) this.renderer.removeBody(id);
    this.known.delete(id);
    this.occluders.delete(id);
    this.visible.delete(id);
  }

  private applyEvent(e: SimEvent): void {
    if (this.onEvent) {
      const k = e.type === 'bodyRemoved' ? this.known.get(e.bodyId) : undefined;
      this.onEvent(e, k ? { descriptor: k.descriptor, pose: this.renderer.store.pose(k.descriptor.id) } : null);
    }
    switch (e.type) {
      case 'sensorEnter':
      case 'sensorExit': {
        const set = this.occupants.get(e.sensorId) ?? new Set<number>();
        this.occupants.set(e.sensorId, set);
        const wasOccupied = set.size > 0;
        if (e.type === 'sensorEnter') set.add(e.bodyId);
        else set.delete(e.bodyId);
        const occupied = set.size > 0;
        if (occupied !== wasOccupied) {
          const color = this.known.get(e.sensorId)?.descriptor.color;
          if (color) this.renderer.store.setStyle(e.sensorId, occupied ? { emissive: OCCUPIED_EMISSIVE, color } : { emissive: 0, color: shade(color, IDLE_SENSOR_SHADE) });
          if (e.playerId !== undefined) this.log(`player #${e.playerId} ${e.type === 'sensorEnter' ? 'entered' : 'left'} zone ${e.sensorId}`);
        }
        return;
      }
      case 'bodyRemoved':
        this.forget(e.bodyId);
        for (const set of this.occupants.values()) set.delete(e.bodyId);
        return;
      case 'playerJoined':
        this.log(`${e.name} (#${e.playerId}) joined`);
        return;
      case 'playerLeft':
        this.log(`player #${e.playerId} left`);
        return;
      case 'scenario':
        this.log(scenarioEventText(e.name, e.value));
        return;
      case 'bodySpawned':
        return;
    }
  }
}

function shade(c: readonly [number, number, number], k: number): [number, number, number] {
  return [c[0] * k, c[1] * k, c[2] * k];
}

function sameLook(a: BodyDescriptor, b: BodyDescriptor): boolean {
  return a.motion === b.motion && a.hidden === b.hidden && a.color.every((c, i) => c === b.color[i]) && JSON.stringify(a.shape) === JSON.stringify(b.shape);
}

/** A readable line for a scenario event ('door' 1 → "door opened"). */
export function scenarioEventText(name: string, value: number): string {
  if (name === 'door') return value ? 'door opened' : 'door closed';
  return `${name}: ${value}`;
}
