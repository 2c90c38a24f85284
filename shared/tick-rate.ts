// The fixed tick every simulation and server room runs at, defined once: physics steps, tick records, the server's
// tick loop, logs and the protocol's welcome all read it from here. Pure data.

/** Ticks per second of every simulation. */
export const TICK_RATE_HZ = 60;
/** Seconds per tick: the physics step (exactly one collision step per tick). */
export const TICK_DT_SECONDS = 1 / TICK_RATE_HZ;
/** Milliseconds per tick: how far apart ticks are due on the server's clock. */
export const TICK_MS = 1000 / TICK_RATE_HZ;
