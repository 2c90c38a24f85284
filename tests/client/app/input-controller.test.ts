// Tests of keyboard/mouse → InputCommand: key mapping, diagonals, sprint with either shift, short presses that still
// count, mouse look in the simulation's yaw convention, and the disabled state.
import { describe, expect, it } from 'vitest';
import { InputController } from '../../../client/app/input-controller.ts';
import { Button, MOVE_STEPS, YAW_STEPS } from '../../../shared/sim/input.ts';

// The controller touches the element only in attach(); these tests drive it through press() and look().
const controller = (): InputController => new InputController({} as HTMLElement);

describe('InputController', () => {
  it('maps WASD and the arrows to walking forward/back and strafing', () => {
    const c = controller();
    c.press('KeyW', true, 0);
    expect(c.sample(0)).toMatchObject({ moveX: 0, moveZ: MOVE_STEPS });
    c.press('KeyW', false, 0);
    c.press('ArrowDown', true, 0);
    c.press('KeyA', true, 0);
    expect(c.sample(0)).toMatchObject({ moveX: -MOVE_STEPS, moveZ: -MOVE_STEPS });
    c.press('ArrowRight', true, 0);
    expect(c.sample(0).moveX).toBe(0); // left and right cancel
    c.press('ArrowDown', false, 0);
    c.press('ArrowUp', true, 0);
    c.press('KeyS', true, 0);
    expect(c.sample(0).moveZ).toBe(0);
  });

  it('ignores keys that control nothing', () => {
    const c = controller();
    expect(c.press('KeyQ', true, 0)).toBe(false);
    expect(c.sample(0)).toMatchObject({ moveX: 0, moveZ: 0, buttons: 0 });
  });

  it('holds sprint while either shift key is down', () => {
    const c = controller();
    c.press('ShiftLeft', true, 0);
    c.press('ShiftRight', true, 0);
    c.press('ShiftLeft', false, 100);
    expect(c.sample(100).buttons & Button.Sprint).toBe(Button.Sprint);
    c.press('ShiftRight', false, 200);
    expect(c.sample(300).buttons & Button.Sprint).toBe(0);
  });

  it('keeps a press shorter than a tick for the next few samples, then drops it', () => {
    const c = controller();
    c.press('Space', true, 1000);
    c.press('Space', false, 1005);
    expect(c.sample(1010).buttons & Button.Jump).toBe(Button.Jump);
    expect(c.sample(1030).buttons & Button.Jump).toBe(Button.Jump);
    expect(c.sample(1100).buttons & Button.Jump).toBe(0);
  });

  it('turns right for a mouse move to the right and looks up for a move up, in the simulation convention', () => {
    const c = controller();
    c.yawRadians = 0;
    c.pitchRadians = 0;
    c.look(100, 0);
    // Yaw grows counter-clockwise seen from above, so turning right lowers it (wrapping below 0).
    expect(c.yawRadians).toBeGreaterThan(Math.PI);
    expect(c.sample(0).yaw).toBeGreaterThan(YAW_STEPS / 2);
    c.look(0, -100);
    expect(c.pitchRadians).toBeGreaterThan(0);
    expect(c.sample(0).pitch).toBeGreaterThan(0);
    c.look(0, 1e6);
    expect(c.pitchRadians).toBeGreaterThan(-Math.PI / 2);
    c.look(Number.NaN, 5);
    expect(Number.isFinite(c.yawRadians)).toBe(true);
  });

  it('sends a neutral command while disabled', () => {
    const c = controller();
    c.press('KeyW', true, 0);
    c.press('Space', true, 0);
    c.enabled = false;
    expect(c.sample(1)).toMatchObject({ moveX: 0, moveZ: 0, buttons: 0 });
  });
});
