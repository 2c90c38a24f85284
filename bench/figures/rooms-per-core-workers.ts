// Rooms per core with room workers: the rooms-per-core ladder (shape-rain 300, 4 light bots per room) with the rooms in
// 2 worker threads of a server process pinned to the same one CPU, so the figure stays per core; a room's GC pause or
// catch-up then stalls only its own worker's rooms. Judged on the server's own room list (ticks, longest gap between
// tick starts). Also reports the main thread's CPU per client per tick (socket and session work alone).
import type { FigureImpl } from '../lib/figure.ts';
import { runRoomsLadder } from './rooms-per-core.ts';

/** Room workers of the figure's server (the bench machines have 2 cores; the server is pinned to one). */
const ROOM_WORKERS = 2;

/** The rooms-per-core-workers figure. */
export const figure: FigureImpl = { run: (opts) => runRoomsLadder(opts, ROOM_WORKERS) };
