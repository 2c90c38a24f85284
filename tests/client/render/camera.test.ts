// Tests of the cameras: the follow camera's placement and wall pull-in, and the orbit camera's framing and limits.
import { describe, expect, it } from 'vitest';
import { FollowCamera, OrbitCamera } from '../../../client/render/camera.ts';
import { BoxOccluders } from '../../../client/render/occluders.ts';

const I = { x: 0, y: 0, z: 0, w: 1 };

describe('FollowCamera', () => {
  it('sits behind and above the character, looking the way the player looks', () => {
    const cam = new FollowCamera();
    cam.shoulderMetres = 0;
    const v = cam.view([0, 0, 0], 0, 0, 0);
    // Yaw 0 faces −Z: the camera is behind, at +Z, and looks towards −Z.
    expect(v.eye[2]).toBeCloseTo(cam.distanceMetres, 6);
    expect(v.target[2]).toBeLessThan(0);
  });

  it('stays in front of a wall behind the character, rising over it rather than closing in on the head', () => {
    const cam = new FollowCamera();
    cam.shoulderMetres = 0;
    const head: [number, number, number] = [0, cam.heightMetres, 0];
    const far = (eye: number[]): number => Math.hypot(eye[0] - head[0], eye[1] - head[1], eye[2] - head[2]);
    const walls = new BoxOccluders();
    walls.set(7, { x: 0, y: 1, z: 3 }, I, { x: 10, y: 3, z: 0.25 }); // a 4 m wall 3 m behind the player
    const v = cam.view([0, 0, 0], 0, 0, 0, walls);
    expect(v.eye[2]).toBeLessThan(2.75);
    expect(far(v.eye)).toBeGreaterThanOrEqual(cam.minDistanceMetres);
    expect(walls.castRay(head, v.eye as [number, number, number])).toBe(1);
    // A wall lower than the head (a walkway's edge): the camera looks over it from above, not from inside the capsule.
    const low = new BoxOccluders();
    low.set(8, { x: 0, y: 0.75, z: 3 }, I, { x: 10, y: 0.75, z: 0.25 });
    cam.reset();
    const over = cam.view([0, 0, 0], 0, -0.2, 0, low);
    expect(over.eye[1]).toBeGreaterThan(1.5);
    expect(far(over.eye)).toBeGreaterThanOrEqual(cam.minDistanceMetres);
    expect(low.castRay(head, over.eye as [number, number, number])).toBe(1);
    // Walled in on every side up high: it pulls in before the nearest wall.
    const tall = new BoxOccluders();
    tall.set(9, { x: 0, y: 25, z: 1 }, I, { x: 10, y: 25, z: 0.25 });
    cam.reset();
    expect(cam.view([0, 0, 0], 0, 0, 0, tall).eye[2]).toBeLessThan(0.75);
    cam.reset();
    const free = cam.view([0, 0, 0], 0, 0, 0, new BoxOccluders());
    expect(free.eye[2]).toBeCloseTo(cam.distanceMetres, 6);
  });
});

describe('OrbitCamera', () => {
  it('frames a region and keeps looking at its centre while it drifts', () => {
    const cam = new OrbitCamera();
    cam.frame([-20, 0, -10], [20, 30, 10]);
    const a = cam.view(0);
    const b = cam.view(1);
    expect(a.target).toEqual(b.target);
    expect(a.target[0]).toBe(0);
    expect(a.eye).not.toEqual(b.eye);
    const r = (v: { eye: number[]; target: number[] }): number => Math.hypot(v.eye[0] - v.target[0], v.eye[1] - v.target[1], v.eye[2] - v.target[2]);
    expect(r(a)).toBeCloseTo(r(b), 6);
  });

  it('keeps elevation above the ground and the zoom within bounds', () => {
    const cam = new OrbitCamera();
    cam.drag(0, -1e6);
    expect(cam.view(0).eye[1]).toBeGreaterThan(cam.center[1]);
    cam.zoom(1e6);
    expect(cam.radiusMetres).toBeLessThanOrEqual(300);
    cam.zoom(-1e6);
    expect(cam.radiusMetres).toBeGreaterThanOrEqual(3);
  });
});
