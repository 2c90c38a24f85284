// character-course's objective on screen, read from the world's state rather than told: the door is open when the
// kinematic body in the doorway has slid away from the trigger zone's middle; a target stands while a moving body
// sits inside its hidden sensor; hits are the scenario's 'targetHit' events since joining. Knows the course's shape
// (one big trigger zone by the door, small sensors around the targets), nothing of its code.
import type { SnapshotView } from '../../shared/protocol/snapshot-frame.ts';
import type { BodyDescriptor, SimEvent } from '../../shared/sim/types.ts';
import { isBullet } from './decorations.ts';

/** The scenario this objective belongs to. */
export const COURSE_SCENARIO = 'character-course';
/** The door counts as open once it has slid this far from the middle of the doorway (m). */
const DOOR_OPEN_METRES = 0.5;

interface Box {
  id: number;
  centre: { x: number; y: number; z: number };
  half: { x: number; y: number; z: number };
}

/** What the objective shows. */
export interface CourseState {
  /** Null until the door has been seen. */
  doorOpen: boolean | null;
  standing: number;
  targets: number;
  hits: number;
}

const inside = (b: Box, x: number, y: number, z: number, marginMetres: number): boolean =>
  Math.abs(x - b.centre.x) <= b.half.x + marginMetres && Math.abs(y - b.centre.y) <= b.half.y + marginMetres && Math.abs(z - b.centre.z) <= b.half.z + marginMetres;

/** Reads the course's state from descriptors, views and events. */
export class CourseObjective {
  private readonly trigger: Box | null;
  private readonly targetSensors: Box[];
  private readonly descriptor: (id: number) => BodyDescriptor | undefined;
  private hits = 0;

  constructor(statics: readonly BodyDescriptor[], descriptor: (id: number) => BodyDescriptor | undefined) {
    this.descriptor = descriptor;
    const boxes: Box[] = [];
    for (const d of statics) if (d.hidden && d.shape.kind === 'box') boxes.push({ id: d.id, centre: d.position, half: d.shape.halfExtents });
    boxes.sort((a, b) => b.half.x * b.half.y * b.half.z - a.half.x * a.half.y * a.half.z || a.id - b.id);
    this.trigger = boxes[0] ?? null;
    this.targetSensors = boxes.slice(1);
  }

  /** Counts hits. */
  onEvent(e: SimEvent): void {
    if (e.type === 'scenario' && e.name === 'targetHit') this.hits++;
  }

  /** The state in this view. */
  state(view: SnapshotView | null): CourseState {
    const out: CourseState = { doorOpen: null, standing: 0, targets: this.targetSensors.length, hits: this.hits };
    if (!view) return out;
    const standing = new Set<number>();
    let doorDistance = Infinity;
    for (let i = 0; i < view.ids.length; i++) {
      const d = this.descriptor(view.ids[i]);
      if (!d || d.playerId !== undefined) continue;
      const x = view.positions[i * 3];
      const y = view.positions[i * 3 + 1];
      const z = view.positions[i * 3 + 2];
      const t = this.trigger;
      if (d.motion === 'kinematic' && t && inside(t, x, y, z, 0.5)) {
        // The door in the doorway: how far it has slid from the middle of the zone.
        const offset = Math.hypot(x - t.centre.x, z - t.centre.z);
        doorDistance = Math.min(doorDistance, offset);
      } else if (d.motion === 'dynamic' && !isBullet(d)) {
        for (const s of this.targetSensors) if (inside(s, x, y, z, 0.05)) standing.add(s.id);
      }
    }
    out.standing = standing.size;
    if (doorDistance < Infinity) out.doorOpen = doorDistance > DOOR_OPEN_METRES;
    return out;
  }
}

/** The objective as lines of text. */
export function objectiveLines(s: CourseState): string[] {
  const door = s.doorOpen === null ? '' : s.doorOpen ? ' — door open' : ' — door closed';
  return [`1. Open the door: stand in the yellow zone by the wall${door}`, `2. Shoot the targets behind it — ${s.standing} of ${s.targets} standing · ${s.hits} hit${s.hits === 1 ? '' : 's'}`];
}

/** Shows the objective in `root` (a panel), updating the text only when it changes. */
export class ObjectivePanel {
  private readonly root: HTMLElement;
  private shown = '';

  constructor(root: HTMLElement) {
    this.root = root;
  }

  /** Shows these lines (or hides the panel for none). */
  show(lines: readonly string[]): void {
    const text = lines.join('\n');
    if (text === this.shown) return;
    this.shown = text;
    this.root.replaceChildren(...lines.map((l) => Object.assign(document.createElement('div'), { textContent: l })));
    this.root.hidden = lines.length === 0;
  }
}
