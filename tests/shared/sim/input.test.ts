// Tests of the one input validator and the quantizer: every accepted command is canonical (integers in range, never
// −0) and stays the same when validated again; nothing a value holds (getters, Proxies, conversion keys) makes
// validation throw or leak into an error text.
import { describe, expect, it } from 'vitest';
import { BUTTON_MASK, MOVE_STEPS, PITCH_STEPS, quantizeInput, validateInputCommand, validateInputFields, YAW_STEPS, type InputCommand } from '../../../shared/sim/input.ts';
import { Prng } from '../../../shared/sim/prng.ts';
import { EDGE_NUMBERS } from '../../helpers/hostile-frames.ts';
import { hostileValue } from '../../helpers/hostile-values.ts';

/** Why a command is not canonical, or null when it is. */
function notCanonical(c: InputCommand): string | null {
  const ranges: Array<[Exclude<keyof InputCommand, 'game'>, number, number]> = [
    ['moveX', -MOVE_STEPS, MOVE_STEPS],
    ['moveZ', -MOVE_STEPS, MOVE_STEPS],
    ['yaw', 0, YAW_STEPS - 1],
    ['pitch', -PITCH_STEPS, PITCH_STEPS],
    ['buttons', 0, BUTTON_MASK],
  ];
  for (const [k, lo, hi] of ranges) {
    const v = c[k];
    if (!Number.isInteger(v) || v < lo || v > hi) return `${k} = ${v} is not an integer in [${lo}, ${hi}]`;
    if (Object.is(v, -0)) return `${k} is -0`;
  }
  if (Object.keys(c).length !== 5) return `extra fields: ${Object.keys(c).join(', ')}`;
  return null;
}

describe('validateInputCommand', () => {
  it('returns +0, never −0, for inputs that round to zero from below', () => {
    const v = validateInputCommand({ moveX: -0.3, moveZ: -0, yaw: -0.4, pitch: -0.5, buttons: -0 });
    expect(v.ok).toBe(true);
    if (!v.ok) return;
    for (const k of ['moveX', 'moveZ', 'yaw', 'pitch', 'buttons'] as const) expect(Object.is(v.command[k], 0), k).toBe(true);
  });

  it('rounds, clamps and wraps into the canonical command', () => {
    expect(validateInputCommand({ moveX: 126.5, moveZ: -1e300, yaw: -1, pitch: 99999, buttons: 2 ** 40 + 0xff })).toEqual({
      ok: true,
      clamped: true,
      command: { moveX: 127, moveZ: -127, yaw: YAW_STEPS - 1, pitch: PITCH_STEPS, buttons: BUTTON_MASK },
    });
  });

  it('names the field and the value without running the value’s code', () => {
    expect(validateInputCommand({ moveX: { toString: 1, valueOf: 1 }, moveZ: 0, yaw: 0, pitch: 0, buttons: 0 })).toEqual({ ok: false, error: 'moveX must be a number, got an object' });
    expect(validateInputCommand({ moveX: 0, moveZ: 0, yaw: 0, pitch: 0, buttons: 10n ** 30n })).toEqual({ ok: false, error: 'buttons must be a non-negative integer bit set, got a bigint of 100 bits' });
    const getter = Object.defineProperty({}, 'moveX', { get: () => { throw new Error('no'); } });
    expect(validateInputCommand(getter)).toEqual({ ok: false, error: 'input could not be read (a field threw when read)' });
  });

  it('accepts every finite number as a canonical command that validates to itself, over 50,000 raw commands', () => {
    const rng = new Prng(77);
    const problems: string[] = [];
    for (let i = 0; i < 50_000; i++) {
      const field = (steps: number): number => (rng.next() < 0.3 ? rng.pick(EDGE_NUMBERS.filter(Number.isFinite)) : rng.range(-2, 2) * steps);
      const raw = { moveX: field(MOVE_STEPS), moveZ: field(MOVE_STEPS), yaw: field(YAW_STEPS), pitch: field(PITCH_STEPS), buttons: rng.int(0, 64) };
      const v = validateInputCommand(raw);
      if (!v.ok) {
        problems.push(`${JSON.stringify(raw)}: ${v.error}`);
        continue;
      }
      const why = notCanonical(v.command);
      const again = validateInputCommand(v.command);
      if (why) problems.push(`${JSON.stringify(raw)}: ${why}`);
      else if (!again.ok || again.clamped || JSON.stringify(again.command) !== JSON.stringify(v.command)) problems.push(`${JSON.stringify(raw)}: not idempotent`);
    }
    expect(problems.slice(0, 5)).toEqual([]);
  });

  it('never throws and never yields a non-canonical command, over 50,000 hostile values', () => {
    const rng = new Prng(78);
    const problems: string[] = [];
    for (let i = 0; i < 50_000; i++) {
      const v = validateInputCommand(hostileValue(rng, 2));
      if (v.ok) {
        const why = notCanonical(v.command);
        if (why) problems.push(why);
      } else if (typeof v.error !== 'string' || v.error.includes('[object')) problems.push(`bad error text ${String(v.error)}`);
    }
    expect(problems.slice(0, 5)).toEqual([]);
  });
});

describe('quantizeInput', () => {
  it('gives canonical commands for any floats, −0 and tiny negatives included', () => {
    const rng = new Prng(79);
    const problems: string[] = [];
    const edge = [-0, -1e-9, -0.003, 0.003, -1, 1, -1.2, Number.NaN, Number.NEGATIVE_INFINITY];
    for (let i = 0; i < 20_000; i++) {
      const f = (scale: number): number => (rng.next() < 0.3 ? rng.pick(edge) : rng.range(-1.5, 1.5) * scale);
      const c = quantizeInput(f(1), f(1), f(20), f(2), rng.int(0, 255));
      const why = notCanonical(c);
      if (why) problems.push(why);
    }
    expect(problems.slice(0, 5)).toEqual([]);
  });
});

describe('validateInputFields', () => {
  it('gives what validateInputCommand gives for the same fields, clamp flag and game values included, whatever came before', () => {
    const rng = new Prng(11);
    const pick = (): unknown => {
      const r = rng.int(0, 8 - 1);
      if (r < 4) return EDGE_NUMBERS[rng.int(0, EDGE_NUMBERS.length - 1)];
      if (r < 6) return rng.int(0, 4000 - 1) - 2000;
      return r === 6 ? hostileValue(rng) : (rng.int(0, 200 - 1) - 100) / 7;
    };
    for (let i = 0; i < 5000; i++) {
      const game = rng.int(0, 3 - 1) === 0 ? undefined : Array.from({ length: rng.int(0, 4 - 1) }, () => (rng.int(0, 2 - 1) === 0 ? rng.int(0, 3_000_000 - 1) - 1_500_000 : pick()));
      const fields = [pick(), pick(), pick(), pick(), rng.int(0, 2 - 1) === 0 ? rng.int(0, 1 << 20 - 1) : pick(), game] as const;
      const viaObject = validateInputCommand({ moveX: fields[0], moveZ: fields[1], yaw: fields[2], pitch: fields[3], buttons: fields[4], game: fields[5] });
      expect(validateInputFields(...fields)).toEqual(viaObject);
    }
  });

  it('reports a clamp only for the command it validates, never one left over from the call before', () => {
    const clampedOf = (...f: Parameters<typeof validateInputFields>): boolean | null => {
      const v = validateInputFields(...f);
      return v.ok ? v.clamped : null;
    };
    expect(clampedOf(0, 0, 0, 0, 0, [5_000_000])).toBe(true);
    expect(clampedOf(0, 0, 0, 0, 0)).toBe(false);
    expect(clampedOf(0, 0, 0, PITCH_STEPS + 5, 0)).toBe(true);
    expect(clampedOf(0, 0, 0, 0, 0, [1, -2])).toBe(false);
    expect(clampedOf(MOVE_STEPS * 3, 0, 0, 0, 0, [])).toBe(true);
    expect(clampedOf(1, 2, 3, 4, 5, [])).toBe(false);
    expect(validateInputFields(0, 0, 0, 0, 0, [7])).toEqual({ ok: true, command: { moveX: 0, moveZ: 0, yaw: 0, pitch: 0, buttons: 0, game: [7] }, clamped: false });
  });
});
