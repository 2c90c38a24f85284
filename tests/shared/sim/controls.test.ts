// Tests of the shared control conventions: move axes and yaw to a walk velocity, pitch to an aim direction.
import { describe, expect, it } from 'vitest';
import { aimDirection, SPRINT_FACTOR, walkVelocity } from '../../../shared/sim/controls.ts';
import { quantizeInput } from '../../../shared/sim/input.ts';

const cmd = (moveX: number, moveZ: number, yawRadians: number, pitchRadians = 0) => quantizeInput(moveX, moveZ, yawRadians, pitchRadians, 0);

describe('controls', () => {
  it('walks toward -Z when moving forward at yaw 0', () => {
    const v = walkVelocity(cmd(0, 1, 0), 4, false);
    expect(v.x).toBeCloseTo(0, 6);
    expect(v.z).toBeCloseTo(-4, 6);
  });

  it('strafes right toward +X at yaw 0', () => {
    const v = walkVelocity(cmd(1, 0, 0), 4, false);
    expect(v.x).toBeCloseTo(4, 6);
    expect(v.z).toBeCloseTo(0, 6);
  });

  it('turns counter-clockwise seen from above: forward at yaw 90° is -X', () => {
    const v = walkVelocity(cmd(0, 1, Math.PI / 2), 4, false);
    expect(v.x).toBeCloseTo(-4, 5);
    expect(v.z).toBeCloseTo(0, 5);
  });

  it('does not walk diagonals faster than straight lines', () => {
    const v = walkVelocity(cmd(1, 1, 0.3), 4, false);
    expect(Math.sqrt(v.x * v.x + v.z * v.z)).toBeCloseTo(4, 6);
  });

  it('sprints faster by the sprint factor', () => {
    const v = walkVelocity(cmd(0, 1, 0), 4, true);
    expect(-v.z).toBeCloseTo(4 * SPRINT_FACTOR, 6);
  });

  it('stands still with centred sticks', () => {
    const v = walkVelocity(cmd(0, 0, 2), 4, true);
    expect(Math.abs(v.x) + Math.abs(v.z)).toBe(0);
  });

  it('aims along the yaw, tilted up by positive pitch, with unit length', () => {
    const level = aimDirection(cmd(0, 0, 0, 0));
    expect(level.z).toBeCloseTo(-1, 6);
    const up = aimDirection(cmd(0, 0, Math.PI, Math.PI / 4));
    expect(up.y).toBeCloseTo(Math.SQRT1_2, 5);
    expect(up.z).toBeCloseTo(Math.SQRT1_2, 5);
    expect(Math.sqrt(up.x * up.x + up.y * up.y + up.z * up.z)).toBeCloseTo(1, 6);
  });
});
