// The server's real clock: performance.now() and Node timers. Everything time-driven in server/ (tick loop, grace
// periods, rate limits, pings) reads time only through the Clock contract of shared/clock.ts.
import { TimerClock } from '../shared/clock.ts';

/** The real clock of the server process: performance.now() and setTimeout. */
export class SystemClock extends TimerClock<ReturnType<typeof setTimeout>> {
  constructor() {
    super({ now: () => performance.now(), start: (delayMs, fn) => setTimeout(fn, delayMs), cancel: (t) => clearTimeout(t) });
  }
}
