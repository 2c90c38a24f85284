// Tests for server/catch-up-budget.ts and its use by TickClock: overdue ticks past the first of a wake-up run only
// while the thread's budget allows, the rest stay due for the next wake-up, and a room far behind still slows down.
import { describe, expect, it } from 'vitest';
import { CatchUpBudget, type CatchUpGate } from '../../server/catch-up-budget.ts';
import { TickClock } from '../../server/tick-clock.ts';
import { TICK_MS } from '../../shared/tick-rate.ts';

/** A gate that closes once `n` ticks have run (reset by hand between wake-ups). */
class CountingGate implements CatchUpGate {
  spent = 0;
  private readonly n: number;
  constructor(n: number) {
    this.n = n;
  }
  allows(): boolean {
    return this.spent < this.n;
  }
  spend(): void {
    this.spent++;
  }
}

describe('CatchUpBudget', () => {
  it('allows catch-up until a turn has spent its budget, and again in the next turn', async () => {
    const budget = new CatchUpBudget(4);
    budget.spend(3);
    expect(budget.allows()).toBe(true);
    budget.spend(2);
    expect(budget.allows()).toBe(false);
    await new Promise((r) => setImmediate(r));
    expect(budget.allows()).toBe(true);
  });

  it('keeps a TickClock from running overdue ticks back to back past the gate; they run on the next wake-up', () => {
    let now = 0;
    const clock = { nowMs: () => now, setTimer: () => ({}) as never, clearTimer: () => undefined };
    const gate = new CountingGate(2);
    const ticks: number[] = [];
    const tc = new TickClock({ clock, maxCatchUpTicks: 4, catchUp: gate, onTick: (t) => ticks.push(t) });
    tc.poll(); // tick 0
    gate.spent = 0;
    // Ticks 1, 2 and 3 are due: the first runs, the gate lets one more through, the third waits.
    now = 3 * TICK_MS;
    expect(tc.poll()).toBe(2);
    expect(ticks).toEqual([0, 1, 2]);
    gate.spent = 0;
    expect(tc.poll()).toBe(1);
    expect(ticks).toEqual([0, 1, 2, 3]);
    expect(tc.slowdowns).toBe(0);
  });

  it('still gives up time when more than maxCatchUpTicks are overdue, however few ran', () => {
    let now = 0;
    const clock = { nowMs: () => now, setTimer: () => ({}) as never, clearTimer: () => undefined };
    const gate = new CountingGate(0);
    const ticks: number[] = [];
    const tc = new TickClock({ clock, maxCatchUpTicks: 4, catchUp: gate, onTick: (t) => ticks.push(t) });
    tc.poll();
    now = 20 * TICK_MS;
    expect(tc.poll()).toBe(1);
    expect(tc.slowdowns).toBe(1);
    expect(tc.skippedTicks).toBeGreaterThan(15);
    now += TICK_MS;
    expect(tc.poll()).toBe(1);
  });
});
