// Keyboard and mouse → InputCommand: WASD/arrows move, mouse (pointer lock) looks, space jumps, click fires,
// shift sprints, E uses. Keeps look angles locally (the camera reads them) and latches short presses for one tick.
import { Button, quantizeInput, type InputCommand } from '../../shared/sim/input.ts';

/** Radians of turn per pixel of mouse movement. */
const MOUSE_RADIANS_PER_PX = 0.0025;
const MAX_PITCH_RADIANS = 1.45;
const TWO_PI = Math.PI * 2;
/** How long a short press of a button keeps counting (ms): three ticks. */
const LATCH_MS = 50;

const MOVE_KEYS: Readonly<Record<string, [number, number]>> = {
  KeyW: [0, 1],
  ArrowUp: [0, 1],
  KeyS: [0, -1],
  ArrowDown: [0, -1],
  KeyA: [-1, 0],
  ArrowLeft: [-1, 0],
  KeyD: [1, 0],
  ArrowRight: [1, 0],
};

const BUTTON_KEYS: Readonly<Record<string, number>> = {
  Space: Button.Jump,
  ShiftLeft: Button.Sprint,
  ShiftRight: Button.Sprint,
  KeyE: Button.Use,
};

/** Turns DOM input on `element` (the canvas) into commands; attach() to listen, detach() to stop. */
export class InputController {
  /** Look direction in the simulation's convention (0 faces −Z, counter-clockwise from above). */
  yawRadians = 0;
  /** Positive looks up. */
  pitchRadians = -0.15;
  /** Whether keys are read at all (false while a menu or message has focus). */
  enabled = true;
  /** Whether a click captures the mouse (false while the orbit camera is in use: there a drag turns the view). */
  captureOnClick = true;

  private readonly element: HTMLElement;
  private readonly keys = new Set<string>();
  private held = 0;
  /** Button bit → time (ms) until which a press counts even if already released. */
  private readonly latchedUntil = new Map<number, number>();
  /** The browser refused pointer lock: clicks fire without it and a right-drag looks. */
  private lockRefused = false;
  private readonly listeners: Array<[EventTarget, string, EventListener]> = [];
  /** Called when a movement key goes down (not on auto-repeat), after the key is applied: sample() includes it. */
  onMoveKeyDown: ((atMs: number) => void) | null = null;

  constructor(element: HTMLElement) {
    this.element = element;
  }

  /** Whether the mouse is captured for looking. */
  get pointerLocked(): boolean {
    return document.pointerLockElement === this.element;
  }

  /** Starts listening to the keyboard, the mouse and focus changes. */
  attach(): void {
    if (this.listeners.length > 0) return;
    this.listen(window, 'keydown', (e) => this.onKey(e as KeyboardEvent, true));
    this.listen(window, 'keyup', (e) => this.onKey(e as KeyboardEvent, false));
    this.listen(window, 'blur', () => this.releaseAll());
    this.listen(document, 'visibilitychange', () => {
      if (document.hidden) this.releaseAll();
    });
    this.listen(this.element, 'mousedown', (e) => this.onMouseDown(e as MouseEvent));
    this.listen(window, 'mouseup', (e) => {
      if ((e as MouseEvent).button === 0) this.held &= ~Button.Fire;
    });
    this.listen(document, 'mousemove', (e) => {
      const m = e as MouseEvent;
      // Pointer lock looks freely; without it (refused, or not yet clicked) a right-button drag looks.
      if (this.pointerLocked || (m.buttons & 2) !== 0) this.look(m.movementX, m.movementY);
    });
    this.listen(this.element, 'contextmenu', (e) => e.preventDefault());
  }

  /** Stops listening and releases everything held. */
  detach(): void {
    for (const [target, type, fn] of this.listeners) target.removeEventListener(type, fn);
    this.listeners.length = 0;
    this.releaseAll();
    if (this.pointerLocked) document.exitPointerLock();
  }

  /** Turns the view by a mouse movement in pixels (right turns right, up looks up). */
  look(dxPx: number, dyPx: number): void {
    if (!Number.isFinite(dxPx) || !Number.isFinite(dyPx)) return;
    this.yawRadians = (((this.yawRadians - dxPx * MOUSE_RADIANS_PER_PX) % TWO_PI) + TWO_PI) % TWO_PI;
    this.pitchRadians = Math.max(-MAX_PITCH_RADIANS, Math.min(MAX_PITCH_RADIANS, this.pitchRadians - dyPx * MOUSE_RADIANS_PER_PX));
  }

  /** Move axes in [-1, 1] from the keys held now: x strafes right, z walks forward. */
  moveAxes(): { x: number; z: number } {
    let x = 0;
    let z = 0;
    for (const code of this.keys) {
      const m = MOVE_KEYS[code];
      if (m) {
        x += m[0];
        z += m[1];
      }
    }
    return { x: Math.max(-1, Math.min(1, x)), z: Math.max(-1, Math.min(1, z)) };
  }

  /**
   * The command for the coming ticks. A press shorter than a tick still counts: it stays set for LATCH_MS after it
   * happened, so the library's next send (which may come after a later sample) carries it.
   */
  sample(nowMs: number = performance.now()): InputCommand {
    let latched = 0;
    for (const [bit, until] of this.latchedUntil) {
      if (until > nowMs) latched |= bit;
      else this.latchedUntil.delete(bit);
    }
    const buttons = this.enabled ? this.held | latched : 0;
    const move = this.enabled ? this.moveAxes() : { x: 0, z: 0 };
    return quantizeInput(move.x, move.z, this.yawRadians, this.pitchRadians, buttons);
  }

  private listen(target: EventTarget, type: string, fn: EventListener): void {
    target.addEventListener(type, fn);
    this.listeners.push([target, type, fn]);
  }

  private onKey(e: KeyboardEvent, down: boolean): void {
    if (!this.enabled || e.ctrlKey || e.metaKey || e.altKey) return;
    const target = e.target as HTMLElement | null;
    if (target && (target.tagName === 'INPUT' || target.tagName === 'TEXTAREA' || target.isContentEditable)) return;
    if (!this.press(e.code, down)) return;
    e.preventDefault();
    if (down && !e.repeat && e.code in MOVE_KEYS) this.onMoveKeyDown?.(performance.now());
  }

  /** Applies a key (a KeyboardEvent.code) going down or up; returns false for keys that control nothing. */
  press(code: string, down: boolean, nowMs: number = performance.now()): boolean {
    const isMove = code in MOVE_KEYS;
    const bit = BUTTON_KEYS[code] ?? 0;
    if (!isMove && bit === 0) return false;
    if (down) this.keys.add(code);
    else this.keys.delete(code);
    if (bit) {
      if (down) {
        this.held |= bit;
        this.latchedUntil.set(bit, nowMs + LATCH_MS);
      } else if (!this.anyKeyHolds(bit)) {
        // Released only when no other key for the same button (the other shift key) is still down.
        this.held &= ~bit;
      }
    }
    return true;
  }

  private anyKeyHolds(bit: number): boolean {
    for (const code of this.keys) if (BUTTON_KEYS[code] === bit) return true;
    return false;
  }


  private onMouseDown(e: MouseEvent): void {
    if (!this.enabled || e.button !== 0) return;
    if (!this.pointerLocked && !this.lockRefused) {
      if (!this.captureOnClick) return;
      // The first click captures the mouse for looking; it does not fire.
      try {
        const request = this.element.requestPointerLock() as unknown;
        if (request instanceof Promise) request.catch(() => (this.lockRefused = true));
      } catch {
        this.lockRefused = true;
      }
      return;
    }
    this.held |= Button.Fire;
    this.latchedUntil.set(Button.Fire, performance.now() + LATCH_MS);
  }

  private releaseAll(): void {
    this.keys.clear();
    this.held = 0;
    this.latchedUntil.clear();
  }
}
