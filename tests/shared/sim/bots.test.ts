// Tests of scripted bots: records valid for the simulation, joins and leaves at the given ticks, the same crowd from
// the same seed, and bots that really walk, turn, jump and fire.
import { describe, expect, it } from 'vitest';
import { BotScript } from '../../../shared/sim/bots.ts';
import { Button } from '../../../shared/sim/input.ts';
import { validateTickRecord } from '../../../shared/sim/tick-record.ts';

describe('bots', () => {
  it('produces records the simulation accepts, tick after tick', () => {
    const script = new BotScript({ seed: 1, bots: 5, joinTicks: [0, 3, 3, 40, 90], leaveTicks: [-1, 50, -1, 60, -1] });
    const present = new Set<number>();
    for (let t = 0; t < 200; t++) {
      const rec = validateTickRecord(script.next(), t, (id) => present.has(id));
      for (const id of rec.leaves) present.delete(id);
      for (const j of rec.joins) present.add(j.playerId);
      expect(rec.commands.map((c) => c.playerId)).toEqual([...present].sort((a, b) => a - b));
    }
  });

  it('joins and leaves at the given ticks with consecutive player ids', () => {
    const recs = new BotScript({ seed: 2, bots: 3, firstPlayerId: 100, joinTicks: [0, 5, 5], leaveTicks: [-1, 8, -1] }).take(10);
    expect(recs[0].joins).toEqual([{ playerId: 100, name: 'bot-100' }]);
    expect(recs[5].joins.map((j) => j.playerId)).toEqual([101, 102]);
    expect(recs[8].leaves).toEqual([101]);
    expect(recs[9].commands.map((c) => c.playerId)).toEqual([100, 102]);
  });

  it('spaces default joins by joinSpacingTicks', () => {
    const recs = new BotScript({ seed: 2, bots: 3, joinSpacingTicks: 4 }).take(9);
    expect(recs.flatMap((r, t) => r.joins.map(() => t))).toEqual([0, 4, 8]);
  });

  it('gives the same crowd for the same seed and another for another seed', () => {
    const a = new BotScript({ seed: 'x', bots: 4 }).take(300);
    const b = new BotScript({ seed: 'x', bots: 4 }).take(300);
    const c = new BotScript({ seed: 'y', bots: 4 }).take(300);
    expect(b).toEqual(a);
    expect(c).not.toEqual(a);
  });

  it('walks, strafes, turns, sprints, jumps and fires', () => {
    const inputs = new BotScript({ seed: 9, bots: 4 }).take(600).flatMap((r) => r.commands.map((c) => c.input));
    expect(inputs.some((i) => i.moveZ === 127)).toBe(true);
    expect(inputs.some((i) => i.moveX !== 0)).toBe(true);
    expect(new Set(inputs.map((i) => i.yaw)).size).toBeGreaterThan(100);
    for (const bit of [Button.Jump, Button.Fire, Button.Sprint]) expect(inputs.some((i) => (i.buttons & bit) !== 0)).toBe(true);
    expect(inputs.filter((i) => i.buttons & Button.Fire).length).toBeLessThan(inputs.length / 2);
  });

  it('leaves out Fire when bots must not shoot', () => {
    const inputs = new BotScript({ seed: 9, bots: 4, fire: false }).take(600).flatMap((r) => r.commands.map((c) => c.input));
    expect(inputs.some((i) => (i.buttons & Button.Fire) !== 0)).toBe(false);
  });

  it('rejects impossible scripts with clear errors', () => {
    expect(() => new BotScript({ seed: 1, bots: -1 })).toThrow(/bots must be an integer/);
    expect(() => new BotScript({ seed: 1, bots: 2, joinTicks: [0] })).toThrow(/one tick per bot/);
    expect(() => new BotScript({ seed: 1, bots: 1, joinTicks: [5], leaveTicks: [5] })).toThrow(/leaves \(tick 5\) before it joins/);
  });
});
