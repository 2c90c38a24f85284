// Tests of the per-tick input record validator: tick order, sorted unique ids, presence rules, command checks.
import { describe, expect, it } from 'vitest';
import { Button } from '../../../shared/sim/input.ts';
import { validateTickRecord } from '../../../shared/sim/tick-record.ts';

const idle = { moveX: 0, moveZ: 0, yaw: 0, pitch: 0, buttons: 0 };
const present = (ids: number[]) => (id: number) => ids.includes(id);

describe('tick-record', () => {
  it('accepts a well-formed record and returns a clean copy', () => {
    const raw = { tick: 5, leaves: [2], joins: [{ playerId: 7, name: 'ann' }], commands: [{ playerId: 1, input: { ...idle, buttons: Button.Jump } }, { playerId: 7, input: idle }] };
    const rec = validateTickRecord(raw, 5, present([1, 2]));
    expect(rec).toEqual(raw);
    expect(rec.commands[0].input).not.toBe(raw.commands[0].input);
  });

  it('rejects a record for another tick', () => {
    expect(() => validateTickRecord({ tick: 4, leaves: [], joins: [], commands: [] }, 5, present([]))).toThrow(/tick 4 given, but the simulation is at tick 5/);
  });

  it('rejects non-objects and missing arrays', () => {
    expect(() => validateTickRecord(null, 0, present([]))).toThrow(/must be an object/);
    expect(() => validateTickRecord({ tick: 0, leaves: [], joins: [] }, 0, present([]))).toThrow(/commands must be an array/);
  });

  it('rejects leaves of absent players and joins of present ones', () => {
    expect(() => validateTickRecord({ tick: 0, leaves: [3], joins: [], commands: [] }, 0, present([1]))).toThrow(/player 3 cannot leave/);
    expect(() => validateTickRecord({ tick: 0, leaves: [], joins: [{ playerId: 1, name: 'x' }], commands: [] }, 0, present([1]))).toThrow(/player 1 cannot join/);
  });

  it('allows a player to leave and rejoin in one record', () => {
    const rec = validateTickRecord({ tick: 0, leaves: [1], joins: [{ playerId: 1, name: 'again' }], commands: [{ playerId: 1, input: idle }] }, 0, present([1]));
    expect(rec.joins[0].name).toBe('again');
  });

  it('rejects duplicate and unsorted player ids', () => {
    expect(() => validateTickRecord({ tick: 0, leaves: [], joins: [], commands: [{ playerId: 1, input: idle }, { playerId: 1, input: idle }] }, 0, present([1]))).toThrow(/appears twice/);
    expect(() => validateTickRecord({ tick: 0, leaves: [], joins: [], commands: [{ playerId: 2, input: idle }, { playerId: 1, input: idle }] }, 0, present([1, 2]))).toThrow(/sorted ascending/);
    expect(() => validateTickRecord({ tick: 0, leaves: [2, 1], joins: [], commands: [] }, 0, present([1, 2]))).toThrow(/sorted ascending/);
  });

  it('rejects commands for players who are not in the game', () => {
    expect(() => validateTickRecord({ tick: 0, leaves: [1], joins: [], commands: [{ playerId: 1, input: idle }] }, 0, present([1]))).toThrow(/not in the game/);
  });

  it('rejects bad player ids and names', () => {
    expect(() => validateTickRecord({ tick: 0, leaves: [], joins: [{ playerId: -1, name: 'x' }], commands: [] }, 0, present([]))).toThrow(/player id must be an integer/);
    expect(() => validateTickRecord({ tick: 0, leaves: [], joins: [{ playerId: 1.5, name: 'x' }], commands: [] }, 0, present([]))).toThrow(/player id/);
    expect(() => validateTickRecord({ tick: 0, leaves: [], joins: [{ playerId: 1, name: 5 }], commands: [] }, 0, present([]))).toThrow(/name string/);
    expect(() => validateTickRecord({ tick: 0, leaves: [], joins: [{ playerId: 1, name: 'é'.repeat(600) }], commands: [] }, 0, present([]))).toThrow(/longer than 1024 bytes/);
  });

  it('rejects NaN, Infinity and wrong types in commands', () => {
    for (const bad of [{ ...idle, moveX: NaN }, { ...idle, yaw: Infinity }, { ...idle, pitch: '3' }, { ...idle, buttons: 1.5 }, 'fire', null]) {
      expect(() => validateTickRecord({ tick: 0, leaves: [], joins: [], commands: [{ playerId: 1, input: bad }] }, 0, present([1]))).toThrow(/command of player 1 is invalid/);
    }
  });

  it('rejects commands the validator would clamp (they are not what the log stores)', () => {
    expect(() => validateTickRecord({ tick: 0, leaves: [], joins: [], commands: [{ playerId: 1, input: { ...idle, moveX: 500 } }] }, 0, present([1]))).toThrow(/out of range/);
    expect(() => validateTickRecord({ tick: 0, leaves: [], joins: [], commands: [{ playerId: 1, input: { ...idle, moveZ: 0.5 } }] }, 0, present([1]))).toThrow(/out of range/);
  });
});
