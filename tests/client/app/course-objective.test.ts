// Tests for client/app/course-objective.ts: the door's state, the targets standing and the hits come from the world's
// bodies and events.
import { describe, expect, it } from 'vitest';
import { CourseObjective, objectiveLines } from '../../../client/app/course-objective.ts';
import type { SnapshotView } from '../../../shared/protocol/snapshot-frame.ts';
import type { BodyDescriptor } from '../../../shared/sim/types.ts';

const I = { x: 0, y: 0, z: 0, w: 1 };
const box = (id: number, motion: BodyDescriptor['motion'], hidden: boolean, x: number, y: number, z: number, hx: number, hy: number, hz: number): BodyDescriptor => ({
  id,
  shape: { kind: 'box', halfExtents: { x: hx, y: hy, z: hz } },
  color: [1, 1, 1],
  motion,
  hidden,
  position: { x, y, z },
  rotation: I,
});

const trigger = box(1, 'static', true, 14, 1.25, 10, 3, 1.25, 2);
const sensorA = box(2, 'static', true, 20, 1.5, 6, 0.4, 0.4, 0.4);
const sensorB = box(3, 'static', true, 20, 1.5, 9, 0.4, 0.4, 0.4);
const door = box(4, 'kinematic', false, 14, 1.2, 10, 0.15, 1.2, 1.5);
const cubeA = box(5, 'dynamic', false, 20, 1.5, 6, 0.25, 0.25, 0.25);
const cubeB = box(6, 'dynamic', false, 20, 1.5, 9, 0.25, 0.25, 0.25);
const all = new Map([door, cubeA, cubeB].map((d) => [d.id, d]));

const view = (bodies: Array<[number, number, number, number]>): SnapshotView => ({ ids: bodies.map((b) => b[0]), positions: Float64Array.from(bodies.flatMap((b) => [b[1], b[2], b[3]])), characters: [] }) as unknown as SnapshotView;

describe('course-objective', () => {
  it('reads the door, the standing targets and the hits from the world', () => {
    const o = new CourseObjective([trigger, sensorA, sensorB], (id) => all.get(id));
    expect(o.state(null)).toEqual({ doorOpen: null, standing: 0, targets: 2, hits: 0 });
    expect(o.state(view([[4, 14, 1.2, 10], [5, 20, 1.5, 6], [6, 20, 1.5, 9]]))).toEqual({ doorOpen: false, standing: 2, targets: 2, hits: 0 });
    o.onEvent({ type: 'scenario', tick: 5, name: 'targetHit', value: 1 });
    o.onEvent({ type: 'scenario', tick: 6, name: 'door', value: 1 });
    // The door slid 2 m into the wall; cube B lies on the ground.
    const later = o.state(view([[4, 14, 1.2, 8], [5, 20, 1.5, 6], [6, 21, 0.25, 9]]));
    expect(later).toEqual({ doorOpen: true, standing: 1, targets: 2, hits: 1 });
    expect(objectiveLines(later)).toEqual(['1. Open the door: stand in the yellow zone by the wall — door open', '2. Shoot the targets behind it — 1 of 2 standing · 1 hit']);
  });
});
