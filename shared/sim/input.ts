// Player input commands: the quantized wire/log form, the one validator every input passes, and conversions.
// Everything a player can influence enters the simulation through a validated InputCommand; nothing else reaches Jolt.
import { describeValue } from './describe-value.ts';

/** Button bits of InputCommand.buttons. */
export const Button = {
  Jump: 1,
  Fire: 2,
  Sprint: 4,
  Use: 8,
} as const;

/** All defined button bits. */
export const BUTTON_MASK = Button.Jump | Button.Fire | Button.Sprint | Button.Use;

/** Quantization steps: move axes in 1/127, yaw in 1/65536 turn, pitch in 1/32768 half-turn. */
export const MOVE_STEPS = 127;
export const YAW_STEPS = 65536;
export const PITCH_STEPS = 16384; // ±16384 ↔ ±π/2

/**
 * One player's input for one tick, quantized to integers so the log, the wire and the simulation agree exactly.
 * moveX/moveZ ∈ [-127, 127] (scaled to [-1, 1]), yaw ∈ [0, 65535] (a full turn), pitch ∈ [-16384, 16384] (±90°).
 */
export interface InputCommand {
  moveX: number;
  moveZ: number;
  yaw: number;
  pitch: number;
  buttons: number;
  /**
   * Game-defined input values (ScenarioDefinition.input), one integer per declared field in name order; absent or
   * empty when the scenario declares none. The simulation fills a missing array with zeros.
   */
  game?: readonly number[];
}

/** Most game input values one command may carry (the scenario's declaration bounds them further). */
export const MAX_COMMAND_GAME_VALUES = 16;
/** Largest magnitude of one game input value. */
export const MAX_COMMAND_GAME_ABS = 1_000_000;

/** The idle command: no movement, facing yaw 0, level. */
export const NEUTRAL_INPUT: Readonly<InputCommand> = Object.freeze({ moveX: 0, moveZ: 0, yaw: 0, pitch: 0, buttons: 0 });

/** The result of validating untrusted input: a clean command, or the reason it was rejected. */
export type InputValidation = { ok: true; command: InputCommand; clamped: boolean } | { ok: false; error: string };

/**
 * The canonical integer nearest to a finite number: rounded half up, then +0 for any zero. Math.round(-0.3) is −0,
 * and −0 must never reach the simulation: its sign survives arithmetic (a walk velocity of −0), the state hash sees
 * those bits, and the log cannot store it.
 */
function canonicalInt(value: number): number {
  return Math.round(value) + 0;
}

/** Whether the last intIn (or gameValues) call had to clamp: a scratch slot read right after each call. */
let lastClamped = false;

/** The canonical integer of `value` in [min, max] (clamped; lastClamped says whether it changed), or why it is no number. */
function intIn(value: unknown, min: number, max: number, field: string): number | string {
  if (typeof value !== 'number') return `${field} must be a number, got ${describeValue(value)}`;
  if (!Number.isFinite(value)) return `${field} must be finite, got ${describeValue(value)}`;
  const r = canonicalInt(value);
  if (r < min) {
    lastClamped = true;
    return min;
  }
  if (r > max) {
    lastClamped = true;
    return max;
  }
  lastClamped = r !== value;
  return r;
}

// Runs once per command of every input message: no result object per field (inputs are the server's main allocation).
function validate(rawMoveX: unknown, rawMoveZ: unknown, rawYaw: unknown, rawPitch: unknown, rawButtons: unknown, rawGame: unknown): InputValidation {
  const moveX = intIn(rawMoveX, -MOVE_STEPS, MOVE_STEPS, 'moveX');
  if (typeof moveX === 'string') return { ok: false, error: moveX };
  let clamped = lastClamped;
  const moveZ = intIn(rawMoveZ, -MOVE_STEPS, MOVE_STEPS, 'moveZ');
  if (typeof moveZ === 'string') return { ok: false, error: moveZ };
  clamped ||= lastClamped;
  const pitch = intIn(rawPitch, -PITCH_STEPS, PITCH_STEPS, 'pitch');
  if (typeof pitch === 'string') return { ok: false, error: pitch };
  clamped ||= lastClamped;
  if (typeof rawYaw !== 'number' || !Number.isFinite(rawYaw)) return { ok: false, error: `yaw must be a finite number, got ${describeValue(rawYaw)}` };
  // Yaw wraps into [0, YAW_STEPS) (the remainder of a huge yaw is exact).
  const yaw = ((canonicalInt(rawYaw) % YAW_STEPS) + YAW_STEPS) % YAW_STEPS;
  if (typeof rawButtons !== 'number' || !Number.isInteger(rawButtons) || rawButtons < 0) {
    return { ok: false, error: `buttons must be a non-negative integer bit set, got ${describeValue(rawButtons)}` };
  }
  const buttons = rawButtons & BUTTON_MASK;
  const game = gameValues(rawGame);
  if (typeof game === 'string') return { ok: false, error: game };
  clamped ||= (game !== null && lastClamped) || yaw !== rawYaw || buttons !== rawButtons;
  const command: InputCommand = { moveX, moveZ, yaw, pitch, buttons };
  if (game !== null && game.length > 0) command.game = game;
  return { ok: true, command, clamped };
}

// Game values: an array of at most MAX_COMMAND_GAME_VALUES finite numbers, each made a canonical integer within
// ±MAX_COMMAND_GAME_ABS (the scenario's own ranges are applied by fitGameInput, which knows them). Null when absent;
// lastClamped says whether any value was clamped.
function gameValues(raw: unknown): number[] | null | string {
  if (raw === undefined) return null;
  if (!Array.isArray(raw)) return `game must be an array of numbers, got ${describeValue(raw)}`;
  if (raw.length > MAX_COMMAND_GAME_VALUES) return `game must have at most ${MAX_COMMAND_GAME_VALUES} values, got ${raw.length}`;
  const values: number[] = [];
  let clamped = false;
  for (let i = 0; i < raw.length; i++) {
    const v = intIn(raw[i], -MAX_COMMAND_GAME_ABS, MAX_COMMAND_GAME_ABS, `game[${i}]`);
    if (typeof v === 'string') return v;
    clamped ||= lastClamped;
    values.push(v);
  }
  lastClamped = clamped;
  return values;
}

/**
 * The one validator for untrusted input (network, log, bots): returns the canonical command (integers in range,
 * never −0) that the simulation, the log and the state hash all use. Wrong types, NaN and Infinity are rejected;
 * out-of-range numbers are clamped (yaw wraps); unknown button bits are dropped. Total: never throws, whatever
 * `raw` is (getters, Proxies and toString/valueOf keys included), and runs none of its code in error texts.
 */
export function validateInputCommand(raw: unknown): InputValidation {
  try {
    if (raw === null || typeof raw !== 'object' || Array.isArray(raw)) return { ok: false, error: 'input must be an object' };
    const r = raw as Record<string, unknown>;
    return validate(r.moveX, r.moveZ, r.yaw, r.pitch, r.buttons, r.game);
  } catch {
    return { ok: false, error: 'input could not be read (a field threw when read)' };
  }
}

/** validateInputCommand for a command's fields already read from a decoded message (no object to build first). */
export function validateInputFields(moveX: unknown, moveZ: unknown, yaw: unknown, pitch: unknown, buttons: unknown, game?: unknown): InputValidation {
  try {
    return validate(moveX, moveZ, yaw, pitch, buttons, game);
  } catch {
    return { ok: false, error: 'input could not be read (a field threw when read)' };
  }
}

/** Quantizes float controls (move axes in [-1, 1], yaw/pitch in radians) into a command. */
export function quantizeInput(moveX: number, moveZ: number, yawRadians: number, pitchRadians: number, buttons: number): InputCommand {
  const clamp = (v: number, lo: number, hi: number): number => (v < lo ? lo : v > hi ? hi : v);
  const fin = (v: number): number => (Number.isFinite(v) ? v : 0);
  const turn = fin(yawRadians) / (2 * Math.PI);
  const yaw = ((Math.round((turn - Math.floor(turn)) * YAW_STEPS) % YAW_STEPS) + YAW_STEPS) % YAW_STEPS;
  return {
    moveX: canonicalInt(clamp(fin(moveX), -1, 1) * MOVE_STEPS),
    moveZ: canonicalInt(clamp(fin(moveZ), -1, 1) * MOVE_STEPS),
    yaw,
    pitch: canonicalInt(clamp(fin(pitchRadians) / (Math.PI / 2), -1, 1) * PITCH_STEPS),
    buttons: (buttons >>> 0) & BUTTON_MASK,
  };
}

/** Yaw of a command in radians, in [0, 2π). */
export function yawRadians(cmd: InputCommand): number {
  return (cmd.yaw / YAW_STEPS) * 2 * Math.PI;
}

/** Pitch of a command in radians, in [-π/2, π/2]. */
export function pitchRadians(cmd: InputCommand): number {
  return (cmd.pitch / PITCH_STEPS) * (Math.PI / 2);
}

/** Whether two commands are identical. */
export function sameInput(a: InputCommand, b: InputCommand): boolean {
  return a.moveX === b.moveX && a.moveZ === b.moveZ && a.yaw === b.yaw && a.pitch === b.pitch && a.buttons === b.buttons && sameGame(a.game, b.game);
}

function sameGame(a: readonly number[] | undefined, b: readonly number[] | undefined): boolean {
  const x = a ?? [];
  const y = b ?? [];
  return x.length === y.length && x.every((v, i) => v === y[i]);
}
