// Tests of input sending: one fixed command per tick, messages that repeat the last few commands, forward-only ticks,
// long jumps, snapshot acks riding on input messages, and the adaptive lead (jitter, boosts on server-reported
// misses, decay).
import { describe, expect, it } from 'vitest';
import { ACK_WAIT_PUMPS, AckCarrier, InputLead, InputSender } from '../../sdk/input-sender.ts';
import { NEUTRAL_INPUT, type InputCommand } from '../../shared/sim/input.ts';

const cmd = (moveX: number): InputCommand => ({ ...NEUTRAL_INPUT, moveX });

describe('input-sender', () => {
  it('sends the newest command with up to three repeats of the previous ticks', () => {
    const s = new InputSender();
    s.setCommand(cmd(1));
    expect(s.update(100)).toEqual({ type: 'input', firstTick: 100, commands: [cmd(1)] });
    s.setCommand(cmd(2));
    expect(s.update(101)).toEqual({ type: 'input', firstTick: 100, commands: [cmd(1), cmd(2)] });
    s.update(102);
    s.setCommand(cmd(3));
    const m = s.update(104)!;
    // Tick 103 and 104 are new (both get the current command); 101 and 102 are repeats.
    expect(m.firstTick).toBe(101);
    expect(m.commands).toEqual([cmd(2), cmd(2), cmd(3), cmd(3)]);
    expect(s.commandFor(101)).toEqual(cmd(2));
  });

  it('sends nothing while the target does not advance and never revisits earlier ticks', () => {
    const s = new InputSender({ redundancy: 2 });
    s.update(50);
    expect(s.update(50)).toBeNull();
    expect(s.update(45)).toBeNull();
    expect(s.update(51)!.firstTick).toBe(50);
    expect(s.newestTick).toBe(51);
  });

  it('covers a jump of many ticks with at most 16 commands and restarts the run after it', () => {
    const s = new InputSender();
    s.update(10);
    const m = s.update(100)!;
    expect(m.firstTick).toBe(85);
    expect(m.commands).toHaveLength(16);
    expect(s.update(101)!.firstTick).toBe(98);
  });

  it('rejects invalid commands and redundancy with clear errors', () => {
    const s = new InputSender();
    expect(() => s.setCommand({ ...NEUTRAL_INPUT, moveX: Number.NaN })).toThrow(/setInput: moveX must be finite/);
    expect(() => new InputSender({ redundancy: 17 })).toThrow(/redundancy/);
    expect(() => s.update(-1)).toThrow(/targetTick/);
  });

  it('puts the newest decoded snapshot tick on the next input message, once', () => {
    const acks = new AckCarrier();
    expect(acks.carry()).toBeUndefined();
    acks.decoded(30);
    acks.decoded(32);
    acks.decoded(31); // an older tick never replaces a newer one
    expect(acks.carry()).toBe(32);
    expect(acks.carry()).toBeUndefined();
    expect(acks.alone()).toBeNull();
  });

  it('sends an ack alone only after it waited a tick of pumps without an input message', () => {
    const acks = new AckCarrier();
    acks.decoded(40);
    for (let pump = 1; pump < ACK_WAIT_PUMPS; pump++) expect(acks.alone()).toBeNull();
    expect(acks.alone()).toBe(40);
    expect(acks.alone()).toBeNull();
    // An input message in between takes the ack and starts the wait over.
    acks.decoded(42);
    expect(acks.alone()).toBeNull();
    expect(acks.carry()).toBe(42);
    acks.decoded(44);
    expect(acks.alone()).toBeNull();
  });

  it('leads by the safety margin on a calm link and by twice the jitter more on a jittery one', () => {
    const lead = new InputLead({ tickRateHz: 60 });
    expect(lead.update(0, 0, 0)).toBeCloseTo(0.24, 6); // 4 ms margin of a 16.7 ms tick
    expect(lead.update(20, 0, 0)).toBeCloseTo(2.64, 6); // (2·20 + 4) ms
    expect(lead.update(1000, 0, 0)).toBe(12);
  });

  it('adds a step each time the server reports more missed inputs, then decays after quiet periods', () => {
    const lead = new InputLead({ tickRateHz: 60, decayMs: 5000, boostStepTicks: 1 });
    const calm = lead.update(0, 0, 0);
    expect(lead.update(0, 3, 1000)).toBeCloseTo(calm + 1, 6);
    expect(lead.update(0, 3, 2000)).toBeCloseTo(calm + 1, 6);
    expect(lead.update(0, 5, 3000)).toBeCloseTo(calm + 2, 6);
    expect(lead.boostTicks).toBe(2);
    expect(lead.update(0, 5, 8000)).toBeCloseTo(calm + 1, 6);
    expect(lead.update(0, 5, 13000)).toBeCloseTo(calm, 6);
    expect(lead.update(0, 5, 30000)).toBeCloseTo(calm, 6);
    const fine = new InputLead({ tickRateHz: 60 });
    const base = fine.update(0, 0, 0);
    expect(fine.update(0, 2, 100)).toBeCloseTo(base + 0.25, 6); // a quarter tick per report by default
  });
});
