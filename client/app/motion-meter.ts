// Measures key → own motion on screen: a movement key pressed while the own character stands still starts a
// measurement; the first drawn frame that shows the character moved ends it (frames drawn since the key, ms, and the
// frames that drew a world in which the key's first tick had run, yet not the move). Feeds the test hook and the
// latency figures; touches neither input nor rendering.

/** Metres the drawn character must move before the key counts as shown (quantization noise stays below it). */
const MOVED_METRES = 0.005;

/** One measured key → motion. */
export interface KeyToMotion {
  /** Frames drawn after the key up to and including the first that shows the move (1: the very next frame). */
  frames: number;
  /** Milliseconds from the key event to the end of drawing that frame. */
  ms: number;
  /**
   * Frames drawn after the key whose world had run the key's first input tick, yet did not show the move: 0 when
   * every world drawn that contains that tick shows it (as predicted play should); more when the command reached the
   * simulation that was drawn later than its tick (a late input the server replaced by the previous one).
   */
  staleFrames: number;
  /** The first input tick the key's command went into. */
  keyTick: number;
  /** Ticks the world drawn in the frame that showed the move had run (fractional when interpolated). */
  shownAfterTicks: number;
  /**
   * How far that world was ahead of what the server had confirmed (ticks): positive when the page simulated it
   * itself (predicted play), negative when it drew the server's past (interpolated snapshots).
   */
  shownAheadOfServerTicks: number;
}

type Vec3 = readonly [number, number, number];

function distance(a: Vec3, b: Vec3): number {
  return Math.hypot(a[0] - b[0], a[1] - b[1], a[2] - b[2]);
}

/** Tracks one pending measurement at a time; keeps the last result and how many were taken. */
export class KeyToMotionMeter {
  private pending: { atMs: number; framesAtKey: number; keyTick: number; from: Vec3; stale: number } | null = null;
  private lastDrawn: Vec3 | null = null;
  /** Whether the last two frames drew the own character in the same place. */
  private still = false;
  /** The last measurement. */
  last: KeyToMotion | null = null;
  /** Measurements taken. */
  count = 0;

  /**
   * A movement key went down at `atMs`; its command goes into input tick `keyTick` and later. Starts a measurement
   * when the own character was drawn standing still.
   */
  keyDown(atMs: number, framesRendered: number, keyTick: number): void {
    if (this.pending || !this.lastDrawn || !this.still) return;
    this.pending = { atMs, framesAtKey: framesRendered, keyTick, from: this.lastDrawn, stale: 0 };
  }

  /**
   * A frame was drawn (framesRendered counts it) showing the world after `ticks` ticks had run (fractional when
   * interpolated), `aheadOfServerTicks` ahead of what the server had confirmed, the own character at `position`
   * (null: none drawn).
   */
  frameDrawn(nowMs: number, framesRendered: number, ticks: number, aheadOfServerTicks: number, position: Vec3 | null): void {
    if (position === null) {
      this.lastDrawn = null;
      this.still = false;
      this.pending = null;
      return;
    }
    const p = this.pending;
    if (p && distance(position, p.from) > MOVED_METRES) {
      this.last = { frames: framesRendered - p.framesAtKey, ms: nowMs - p.atMs, staleFrames: p.stale, keyTick: p.keyTick, shownAfterTicks: ticks, shownAheadOfServerTicks: aheadOfServerTicks };
      this.count++;
      this.pending = null;
    } else if (p && ticks >= p.keyTick + 1) {
      p.stale++;
    }
    this.still = this.lastDrawn !== null && distance(position, this.lastDrawn) <= MOVED_METRES;
    this.lastDrawn = [position[0], position[1], position[2]];
  }
}
