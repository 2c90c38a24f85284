// One thread's budget for catch-up ticks: every room on a thread shares its event loop, so a late room may run its
// overdue ticks back to back only while the ticks of the current turn have taken less than the budget. Past it, the
// room runs one tick per wake-up and lets the loop serve the other rooms and sockets in between.
/** Milliseconds of ticks one turn of a thread's event loop may run before catch-up ticks wait for the next turn. */
export const DEFAULT_CATCH_UP_BUDGET_MS = 4;

/** What a TickClock asks before running a catch-up tick. */
export interface CatchUpGate {
  /** Whether another catch-up tick may run in this turn. */
  allows(): boolean;
  /** A tick ran for `ms` in this turn. */
  spend(ms: number): void;
}

/** A per-thread CatchUpGate whose spending resets at the end of each turn of the event loop. */
export class CatchUpBudget implements CatchUpGate {
  readonly budgetMs: number;
  private usedMs = 0;
  private resetPending = false;

  constructor(budgetMs = DEFAULT_CATCH_UP_BUDGET_MS) {
    this.budgetMs = budgetMs;
  }

  allows(): boolean {
    return this.usedMs < this.budgetMs;
  }

  spend(ms: number): void {
    this.usedMs += ms;
    if (this.resetPending) return;
    this.resetPending = true;
    setImmediate(() => {
      this.usedMs = 0;
      this.resetPending = false;
    });
  }
}
