// The client library's real clock: performance.now() and setTimeout, available in browsers and Node 24. The Clock
// contract and the ManualClock tests drive live in shared/clock.ts.
import { TimerClock } from '../shared/clock.ts';

/** The real clock of a browser page or Node 24: performance.now() and setTimeout. */
export class RealClock extends TimerClock<ReturnType<typeof setTimeout>> {
  constructor() {
    super({ now: () => performance.now(), start: (delayMs, fn) => setTimeout(fn, delayMs), cancel: (t) => clearTimeout(t) });
  }
}
